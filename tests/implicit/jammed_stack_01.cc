// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The implicit contact inequality at large steps on a packing that carries
// load from the start. Nine disks (R = 0.1, 6.4 cells per radius) stacked
// three by three on the floor, against the left wall and touching each
// other, Coulomb friction 0.3, gap check on, are compressed by a rigid
// platen that starts 0.2 cells above the top row and moves down at
// V = 0.037 (V / c = 1e-3) to t = 0.3 (0.7 cells of travel).
//
// Reference: the explicit leapfrog at CFL 0.25 (2845 steps). The implicit
// theta = 1/2 scheme with the shipped solver at 30 and 100 times the
// explicit step must give the platen work within 8 % of it. A caught field
// that lost its whole approach (the law before the inequality) held the
// disks a fraction of a cell apart: +13 % at 30 times and +84 % at 100
// times. Also checked in each implicit run: the work of the constraints
// (booked as friction work) is not negative, and no step is rejected.
// The steps are fixed (Maximum CFL number = 0): the test is of the contact
// inequality at those steps; tests/implicit/step_growth_01 grows them.

#include <grainmpm/simulator.h>

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
    run_case("explicit",
             stack_case("  set Scheme = explicit leapfrog\n"
                        "  set CFL number = 0.25\n"));
  const double reference = explicit_run.at("boundary_work").back();
  deallog << "explicit: " << explicit_run.at("time").size() - 1
          << " steps, platen work > 0: " << (reference > 0. ? "yes" : "no")
          << std::endl;

  for (const auto &[name, setting] :
       {std::pair<std::string, std::string>{"implicit-30",
                                            "  set CFL number = 7.5\n"},
        {"implicit-100", "  set Time step = 1.0647e-2\n"}})
    {
      const auto   energy   = run_case(name,
                                   stack_case("  set Scheme = implicit theta\n"
                                                  "  set Theta = 0.5\n"
                                                  "  set Maximum CFL number = 0\n" +
                                              setting));
      const double work     = energy.at("boundary_work").back();
      double       rejected = 0.;
      for (const double r : energy.at("rejected_steps"))
        rejected += r;
      deallog << name << ": platen work within 8 % of explicit: "
              << (std::abs(work / reference - 1.) < 0.08 ? "yes" : "no")
              << std::endl;
      deallog << name << ": constraint work not negative: "
              << (energy.at("friction_work").back() >= 0. ? "yes" : "no")
              << std::endl;
      deallog << name
              << ": no rejected step: " << (rejected == 0. ? "yes" : "no")
              << std::endl;
    }
}
