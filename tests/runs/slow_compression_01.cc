// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The shipped slow compression of 30 disks (prm/slow_compression_implicit
// .prm and prm/slow_compression_explicit.prm) to t = 0.1, judged by the
// energy the platen puts in (boundary work W) and what the disks hold at
// the end (kinetic + elastic energy E):
// - implicit theta = 1/2: E / W = 0.993 (the transfers lose 0.8 % of W);
// - explicit, Stress update = USL (the shipped explicit case): W within
//   2.3 % of the implicit one, E / W = 0.91 (energy lost, not created);
// - explicit with the default USF: the strain velocity differs from the
//   velocity that moves the points at the constraints, and the scheme
//   creates energy under sustained contact: E / W = 1.39, W 11 % high.

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

std::pair<double, double>
compress(const std::string &name,
         const std::string &prm_file,
         const std::string &stress_update)
{
  const auto c =
    run_case(name,
             "include " GRAINMPM_SOURCE_DIR "/prm/" + prm_file +
               "\nsubsection Time stepping\n  set End time = 0.1\n" +
               (stress_update.empty() ?
                  std::string() :
                  "  set Stress update = " + stress_update + "\n") +
               "end\n");
  return {c.at("boundary_work").back(), c.at("total_energy").back()};
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const auto [W_implicit, E_implicit] =
    compress("implicit", "slow_compression_implicit.prm", "");
  const auto [W_usl, E_usl] =
    compress("usl", "slow_compression_explicit.prm", "");
  const auto [W_usf, E_usf] =
    compress("usf", "slow_compression_explicit.prm", "USF");

  const auto yes = [](const bool b) { return b ? "yes" : "no"; };
  deallog << "implicit: E / W within [0.97, 1.0]: "
          << yes(E_implicit / W_implicit > 0.97 && E_implicit <= W_implicit)
          << std::endl;
  deallog << "explicit USL: W within 5 % of the implicit W: "
          << yes(std::abs(W_usl / W_implicit - 1.) < 0.05)
          << ", E / W <= 1 (no energy created): " << yes(E_usl <= W_usl)
          << ", E / W >= 0.85: " << yes(E_usl >= 0.85 * W_usl) << std::endl;
  deallog << "explicit USF: E / W > 1.2 (energy created): "
          << yes(E_usf > 1.2 * W_usf) << ", W more than 5 % above implicit: "
          << yes(W_usf > 1.05 * W_implicit) << std::endl;
}
