// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Time stepping/Quasi-static theta on a slow approach: the jammed stack of
// jammed_stack.h compressed at V / c = 1e-5 (V = 3.7e-4) to t = 1.4, the
// implicit scheme with every other entry at its default (steps from CFL
// 0.25 grown up to Maximum CFL number 250).
//
// Reference: the explicit leapfrog, update stress last, at CFL 0.25.
//
// A step whose grid kinetic energy is at most 1 % of the elastic energy at
// both ends is quasi-static, and the next step is centred at
// max(Theta, Quasi-static theta) = 0.6. The stack starts at rest with no
// elastic energy, so the first steps keep Theta = 1/2; once the platen
// has loaded it and its vibration has settled, the steps take 0.6 (the
// column theta of energy.csv), and the damping lets them grow: from the
// first step at 0.6 to the end the run must take at most half the steps
// that the same run with Quasi-static theta = 0 (Theta = 1/2 in every
// step) takes over that interval, with the platen work and the elastic
// energy of both within 5 % of the explicit run's. Measured: the two runs
// are the same to t = 0.79 (108 steps), where the grid kinetic energy, that
// of the compression itself, falls below 1 % of the elastic energy; then
// 14 steps at 0.6 against 42 at 1/2 (122 and 150 in all). With `Contact/
// Shape gap = false`: the switch at t = 0.79 too, then 22 steps against 82
// (109 and 169 in all).
//
// The nominal step of these runs, CFL 0.25, is below the explicit stable
// step, and a rejected grown step must be retried implicitly at half its
// length, not advanced by the explicit fallback (whose steps would
// resume at the rejected length and be rejected again): no step of the
// default run may be advanced by explicit sub-steps (theta 0 in
// energy.csv). Advanced so, it took 108 fallbacks in its first tenth of
// a time unit and ten times as long.

#include <grainmpm/simulator.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

#include "../energy_csv.h"
#include "jammed_stack.h"

using namespace grainmpm;

namespace
{
  /** The number of steps (rows after t = 0) centred at @p theta. */
  unsigned int
  steps_at(const std::map<std::string, std::vector<double>> &run,
           const double                                      theta)
  {
    const std::vector<double> &column = run.at("theta");
    return std::count_if(column.begin() + 1, column.end(), [&](const double x) {
      return std::abs(x - theta) < 1e-12;
    });
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const auto explicit_run =
    run_case("explicit", slow_stack_case(stack_explicit_reference()));
  const double elastic = explicit_run.at("elastic_energy").back();
  const double work    = explicit_run.at("boundary_work").back();
  deallog << "explicit: elastic energy and platen work > 0: "
          << (elastic > 0. && work > 0. ? "yes" : "no") << std::endl;

  const auto defaults =
    run_case("defaults", slow_stack_case("  set Scheme = implicit theta\n"));
  const auto half = run_case("half",
                             slow_stack_case("  set Scheme = implicit theta\n"
                                             "  set Quasi-static theta = 0\n"));

  const unsigned int n_defaults = defaults.at("theta").size() - 1;
  const unsigned int n_half     = half.at("theta").size() - 1;

  const auto within = [&](const std::map<std::string, std::vector<double>> &run,
                          const std::string &column,
                          const double       reference) {
    return std::abs(run.at(column).back() / reference - 1.) < 0.05;
  };
  for (const auto &[name, run] : {std::make_pair("defaults", &defaults),
                                  std::make_pair("theta 1/2", &half)})
    deallog << name
            << ": elastic energy and platen work within 5 % of explicit: "
            << (within(*run, "elastic_energy", elastic) &&
                    within(*run, "boundary_work", work) ?
                  "yes" :
                  "no")
            << std::endl;

  deallog << "defaults: the first step at Theta = 1/2, the stack at rest: "
          << (defaults.at("theta")[1] == 0.5 ? "yes" : "no") << std::endl;
  deallog << "defaults: every step implicit at 1/2 or 0.6, the last at 0.6: "
          << (steps_at(defaults, 0.5) + steps_at(defaults, 0.6) == n_defaults &&
                  defaults.at("theta").back() == 0.6 ?
                "yes" :
                "no")
          << std::endl;
  deallog << "Quasi-static theta = 0: every step at 1/2: "
          << (steps_at(half, 0.5) == n_half ? "yes" : "no") << std::endl;
  // The steps from the first one at 0.6 to the end, and the steps of the
  // Theta = 1/2 run that end in the same interval.
  const auto        &theta = defaults.at("theta");
  const unsigned int first =
    std::find(theta.begin() + 1, theta.end(), 0.6) - theta.begin();
  const double       switch_time    = defaults.at("time")[first - 1];
  const unsigned int after_defaults = n_defaults + 1 - first;
  unsigned int       after_half     = 0;
  for (unsigned int r = 1; r <= n_half; ++r)
    after_half += (half.at("time")[r] > switch_time);
  deallog << "defaults: at most half the steps at 1/2 from the first step at "
          << "0.6: " << (2 * after_defaults <= after_half ? "yes" : "no")
          << std::endl;
}
