// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The shipped slow compression of 30 disks (prm/slow_compression_implicit
// .prm and prm/slow_compression_explicit.prm) to t = 0.2 (the platen meets
// the top disk at t = 0.09), judged by the energy the platen puts in
// (boundary work W) and what the disks hold at the end (kinetic + elastic
// energy E); measured (GRAINMPM_VERBOSE prints them):
// - implicit theta = 1/2 at 30 times the explicit step (fixed: Maximum CFL
//   number = 0): E / W = 0.968, with 1.2 Newton iterations per step and no
//   rejected step;
// - explicit, Stress update = USL (the shipped explicit case): W within
//   0.3 % of the implicit one, E / W = 0.93 (energy lost, not created);
// - explicit with the default USF: the strain velocity differs from the
//   velocity that moves the points at the constraints, and the scheme
//   creates energy under contact: E / W = 1.26, W 3 % above the implicit
//   one (with `Contact/Shape gap = false`, before 2026-12-07: E / W = 1.22
//   and W 10 % high).
// Before the contact used the platen's exact face (2026-12-03), E / W was
// 0.979 implicit and the grown steps below were -0.5 % from explicit USL.

#include <cstdlib>
#include <iostream>
#include <sstream>

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

struct Compression
{
  double W, E, newton_per_step, rejected, steps;
};



// The shipped case to End time @p end_time, with the entries @p extra in
// subsection Time stepping.
Compression
compress(const std::string &name,
         const std::string &prm_file,
         const std::string &extra,
         const double       end_time = 0.2)
{
  const auto   c      = run_case(name,
                          "include " GRAINMPM_SOURCE_DIR "/prm/" + prm_file +
                            "\nsubsection Time stepping\n  set End time = " +
                            std::to_string(end_time) + "\n" + extra + "end\n");
  const auto  &newton = c.at("newton_iterations");
  const double steps  = newton.size();
  double       sum    = 0.;
  for (const double n : newton)
    sum += n;
  double rejected = 0.;
  for (const double r : c.at("rejected_steps"))
    rejected += r;
  return {c.at("boundary_work").back(),
          c.at("total_energy").back(),
          sum / steps,
          rejected,
          steps};
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  // The implicit run's log, to see that it does not report created
  // energy: the platen meets the top disk at t = 0.09, when the energy
  // reference (the largest kinetic plus elastic energy so far) is still
  // tiny; the balance residual of that step was 0.20 of it and 0.066 of
  // the platen work.
  std::ostringstream log;
  std::streambuf    *console  = std::cout.rdbuf(log.rdbuf());
  const Compression  implicit = compress("implicit",
                                        "slow_compression_implicit.prm",
                                        "  set Maximum CFL number = 0\n");
  std::cout.rdbuf(console);
  std::cout << log.str();
  const Compression usl = compress("usl", "slow_compression_explicit.prm", "");
  const Compression usf = compress("usf",
                                   "slow_compression_explicit.prm",
                                   "  set Stress update = USF\n");

  const auto yes = [](const bool b) { return b ? "yes" : "no"; };
  deallog << "implicit: E / W within [0.96, 1.0]: "
          << yes(implicit.E / implicit.W > 0.96 && implicit.E <= implicit.W)
          << std::endl;
  // At 30 times the explicit step the contact status of a slowly
  // compressed packing is updated after every Newton iteration until it
  // settles (a few slots change at each of the first iterations): 1.8
  // Newton iterations a step (4.6 on the earlier deposit with the classic
  // contact, which loaded many more contacts). With the status fixed after two
  // changes it was 4.0, with an unconverged status; with every update allowed
  // but without the rules that settle it, the solve ran to the cap.
  deallog << "implicit: at most 5 Newton iterations per step on average: "
          << yes(implicit.newton_per_step <= 5.)
          << ", no rejected step: " << yes(implicit.rejected == 0.)
          << std::endl;
  deallog << "implicit: no note of created energy: "
          << yes(log.str().find("created energy") == std::string::npos)
          << std::endl;
  deallog << "explicit USL: W within 5 % of the implicit W: "
          << yes(std::abs(usl.W / implicit.W - 1.) < 0.05)
          << ", E / W <= 1 (no energy created): " << yes(usl.E <= usl.W)
          << ", E / W >= 0.85: " << yes(usl.E >= 0.85 * usl.W) << std::endl;
  deallog << "explicit USF: E / W > 1.2 (energy created): "
          << yes(usf.E > 1.2 * usf.W) << ", W / W(implicit) = " << std::fixed
          << std::setprecision(2) << usf.W / implicit.W << std::defaultfloat
          << std::endl;

  // The shipped case as it is, its steps grown by default, over the whole
  // travel (t = 1): against explicit USL its platen work is -3.2 % in 143
  // steps (fixed steps of the size above take 314). Over the
  // first burst alone (to t = 0.2) the grown steps are +8 %: the steps grow
  // to 240 explicit steps while the platen approaches the packing through
  // empty space, and the energy bound cuts them back at the first impacts.
  const Compression grown =
    compress("grown", "slow_compression_implicit.prm", "", 1.);
  const Compression usl_whole =
    compress("usl_whole", "slow_compression_explicit.prm", "", 1.);
  deallog << "implicit, grown steps, to t = 1: platen work within 4 % of "
             "explicit USL: "
          << yes(std::abs(grown.W / usl_whole.W - 1.) < 0.04)
          << ", fewer than 250 steps (314 fixed): " << yes(grown.steps < 250.)
          << std::endl;
  if (std::getenv("GRAINMPM_VERBOSE") != nullptr)
    for (const auto &[name, c] : {std::pair{"implicit", implicit},
                                  {"USL", usl},
                                  {"USF", usf},
                                  {"grown", grown},
                                  {"USL to t = 1", usl_whole}})
      deallog << name << ": W = " << c.W << ", E / W = " << c.E / c.W
              << ", Newton per step " << c.newton_per_step << std::endl;
}
