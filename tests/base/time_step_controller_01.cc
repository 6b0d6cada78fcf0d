// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// TimeStepController, the implicit failure policy with 20 Newton iterations
// allowed (target N_t = 10) and Steps before growth = 2, nominal step 1: a
// rejected step is halved; a cut step grows by min(2, N_t / N) after two
// easy steps (N <= N_t) in a row and never beyond the nominal step; a hard
// step (N > N_t) starts the count again and changes nothing else; with
// adaptive time stepping off nothing changes and a failure is final.
// Maximum CFL number = 0: the nominal step is the largest.

#include <grainmpm/time_integration/time_step_controller.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  TimeSteppingParameters parameters;
  parameters.scheme              = TimeSteppingScheme::implicit_theta;
  parameters.time_step           = 1.;
  parameters.end_time            = 100.;
  parameters.steps_before_growth = 2;
  parameters.maximum_cfl_number  = 0.;
  TimeStepController controller(parameters, 20, 1., 1.);
  double             step = controller.first_step(0.);
  deallog << "first step " << step << ", minimum "
          << controller.get_minimum_step() << std::endl;

  // Two failures: 1 -> 0.5 -> 0.25.
  for (unsigned int k = 0; k < 2; ++k)
    {
      deallog << "reject " << step << ": retry allowed "
              << controller.reject(step);
      step = controller.retry_step();
      deallog << ", retry with " << step << std::endl;
    }

  // Accepted steps with N Newton iterations: the step after each.
  const auto accept = [&](const unsigned int n) {
    controller.accept(step, n);
    step = controller.next_step(0.);
    deallog << "accepted with N = " << n << ": next step " << step << std::endl;
  };
  accept(4);  // one easy step: no growth yet
  accept(4);  // two: x min(2, 10 / 4) = 2 -> 0.5
  accept(8);  // easy, count 1
  accept(8);  // count 2: x 10 / 8 -> 0.625
  accept(16); // hard: the count starts again, no shrinking
  accept(8);  // count 1
  accept(40); // hard: count 0
  accept(1);
  accept(1); // x 2 -> 1.25: the nominal step 1
  accept(1); // at the nominal step nothing changes
  deallog << "smallest step tried " << controller.smallest_step_tried()
          << std::endl;

  // Adaptive time stepping off: no change, no retry.
  parameters.adaptive_time_stepping = false;
  TimeStepController fixed(parameters, 20, 1., 1.);
  step = fixed.first_step(0.);
  fixed.accept(step, 19);
  deallog << "adaptive off: after N = 19 the next step is "
          << fixed.next_step(0.)
          << ", a failure may be retried: " << fixed.reject(step) << std::endl;
}
