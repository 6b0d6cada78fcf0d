// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// TimeStepController with growth beyond the nominal step: nominal step 1,
// Maximum time step = 10, Maximum displacement per step = 0.1 on cells of
// size 1, 20 Newton iterations allowed (N_t = 10), Steps before growth = 2.
// Easy steps grow the step by min(2, N_t / N) up to 10; points moving at
// speed v hold it at 0.1 / v, never below the nominal step, and it grows
// again from there; where the speed of the grains is given, it holds the
// step instead of the points' speed; a rejected step is halved and grows
// back; hard steps do not grow it. The entries are refused for the
// explicit scheme, without adaptive steps and below a fixed Time step.

#include <grainmpm/base/input_error.h>
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
  parameters.scheme               = TimeSteppingScheme::implicit_theta;
  parameters.time_step            = 1.;
  parameters.maximum_time_step    = 10.;
  parameters.maximum_displacement = 0.1;
  parameters.end_time             = 1000.;
  parameters.steps_before_growth  = 2;
  TimeStepController controller(parameters, 20, 1., 1.);
  double             step = controller.first_step(0.);
  deallog << "first step " << step << std::endl;

  // Accepted steps with N Newton iterations after which the points move
  // at most at speed v: the step after each.
  const auto accept = [&](const unsigned int n, const double v) {
    controller.accept(step, n);
    step = controller.next_step(v);
    deallog << "accepted with N = " << n << ", v = " << v << ": next step "
            << step << std::endl;
  };
  accept(2, 0.); // one easy step: no growth yet
  accept(2, 0.); // x 2 -> 2
  accept(5, 0.);
  accept(5, 0.); // x 2 -> 4
  accept(8, 0.);
  accept(8, 0.); // x 10 / 8 -> 5
  accept(1, 0.);
  accept(1, 0.);   // x 2 -> 10: the maximum
  accept(1, 0.);   // held at the maximum
  accept(1, 0.);   // still 10
  accept(15, 0.);  // hard: no change
  accept(1, 0.04); // 0.1 / 0.04 = 2.5
  accept(1, 0.04); // grows from 2.5 but is held at 2.5
  accept(1, 0.);   // 2.5, the count starts again
  accept(1, 0.);   // x 2 -> 5
  accept(1, 1.);   // 0.1 / 1 is below the nominal step: 1
  accept(1, 0.);   // count 2: grows from 1 -> 2
  deallog << "reject " << step << ": retry allowed " << controller.reject(step);
  step = controller.retry_step();
  deallog << ", retry with " << step << std::endl;
  accept(1, 0.); // 1
  accept(1, 0.); // x 2 -> 2
  accept(1, 0.);
  accept(1, 0.); // 4

  // Where the speed of the grains' rigid-body motion is given, the
  // displacement bound takes it instead of the point speed: points at 0.04
  // in grains moving at 0.02 allow 0.1 / 0.02 = 5 (the point speed would
  // hold the step at 2.5), and grains at 0.04 hold it at 2.5.
  const auto accept_grains = [&](const double v, const double grain_speed) {
    controller.accept(step, 1);
    step = controller.next_step(v, grain_speed);
    deallog << "accepted with N = 1, points at " << v << ", grains at "
            << grain_speed << ": next step " << step << std::endl;
  };
  accept_grains(0.04, 0.02); // 4
  accept_grains(0.04, 0.02); // x 2, held at 5
  accept_grains(0.04, 0.04); // 2.5

  // Without a maximum time step: Maximum CFL number times h / c (here 1)
  // bounds the steps (the default, 250, and 3); 0 keeps the nominal step
  // whatever the speed.
  parameters.maximum_time_step = 0.;
  for (const double growth : {250., 3., 0.})
    {
      parameters.maximum_cfl_number = growth;
      TimeStepController nominal(parameters, 20, 1., 1.);
      step = nominal.first_step(0.);
      for (unsigned int k = 0; k < 8; ++k)
        {
          nominal.accept(step, 1);
          step = nominal.next_step(0.);
        }
      deallog << "no maximum time step, Maximum CFL number " << growth
              << ": after eight easy steps the step is " << step << std::endl;
    }

  // The entries that are refused.
  const auto check = [](TimeSteppingParameters p, const std::string &label) {
    try
      {
        p.check();
        deallog << label << ": accepted" << std::endl;
      }
    catch (const InputError &error)
      {
        deallog << label << ": " << error.what() << std::endl;
      }
  };
  TimeSteppingParameters p;
  p.scheme_text       = "implicit theta";
  p.maximum_time_step = 10.;
  check(p, "implicit, Maximum time step 10");
  p.time_step = 20.;
  check(p, "implicit, Time step 20");
  p.time_step              = 0.;
  p.adaptive_time_stepping = false;
  check(p, "implicit, not adaptive");
  p.adaptive_time_stepping = true;
  p.scheme_text            = "explicit leapfrog";
  check(p, "explicit");
}
