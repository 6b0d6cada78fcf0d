// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Steps grown beyond the nominal step (Time stepping/Maximum time step) on
// the jammed stack of jammed_stack.h, compressed at V / c = 1e-3.
//
// Reference: the explicit leapfrog, update stress last, at CFL 0.25. The
// implicit run starts from its nominal step, CFL 7.5 (30 times the
// explicit step), with Maximum time step 300 times the explicit step and
// the other entries at their defaults. Its steps must grow: the median
// step at least twice the nominal one (measured: 102 times the explicit
// step); and the platen work must stay within 5 % of the explicit one
// (measured: +3.0 %). Also checked:
// no step is longer than the maximum, and, as in the fixed-step runs of
// jammed_stack_01, the work of the constraints (booked as friction work)
// is not negative.

#include <grainmpm/simulator.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

#include "../energy_csv.h"
#include "jammed_stack.h"

using namespace grainmpm;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const auto explicit_run =
    run_case("explicit", stack_case(stack_explicit_reference()));
  const double reference = explicit_run.at("boundary_work").back();
  deallog << "explicit: platen work > 0: " << (reference > 0. ? "yes" : "no")
          << std::endl;

  const auto energy =
    run_case("grown",
             stack_case("  set Scheme = implicit theta\n"
                        "  set CFL number = 7.5\n"
                        "  set Maximum time step = " +
                        std::to_string(300. * stack_explicit_step) + "\n"));
  std::vector<double> steps(energy.at("dt").begin() + 1, energy.at("dt").end());
  std::sort(steps.begin(), steps.end());
  // (The last step may be cut short by the End time.)
  const double median = steps[steps.size() / 2] / stack_explicit_step;
  const double largest =
    *std::max_element(steps.begin(), steps.end()) / stack_explicit_step;
  const double work = energy.at("boundary_work").back();
  deallog << "grown: median step at least twice the nominal one: "
          << (median >= 60. ? "yes" : "no") << std::endl;
  deallog << "grown: no step beyond the maximum: "
          << (largest <= 300. * (1. + 1e-12) ? "yes" : "no") << std::endl;
  deallog << "grown: platen work within 5 % of explicit: "
          << (std::abs(work / reference - 1.) < 0.05 ? "yes" : "no")
          << std::endl;
  deallog << "grown: constraint work not negative: "
          << (energy.at("friction_work").back() >= 0. ? "yes" : "no")
          << std::endl;
}
