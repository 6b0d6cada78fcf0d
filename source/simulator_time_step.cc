// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The step of the time loop with its failure policy: retries with smaller
// steps and the explicit fallback of the implicit scheme.

#include <grainmpm/base/input_error.h>
#include <grainmpm/contact/held_contact_status.h>
#include <grainmpm/simulator.h>
#include <grainmpm/time_integration/step_error_estimator.h>

#include <sstream>

namespace grainmpm
{
  template <int dim>
  StepStatistics
  Simulator<dim>::advance_one_step(DiscreteTime &time)
  {
    unsigned int rejected      = 0;
    unsigned int failed_solves = 0;
    for (;;)
      {
        StepStatistics statistics;
        {
          TimerOutput::Scope scope(timer,
                                   implicit ? "implicit step" :
                                              "explicit step");
          statistics = stepper->advance(particle_handler,
                                        time.get_current_time(),
                                        time.get_next_step_size());
        }
        summary.add_attempt(statistics);
        if (statistics.solver.converged)
          {
            statistics.solver.rejected = rejected;
            last_stepper               = stepper.get();
            time_step_controller->accept(time.get_next_step_size(),
                                         statistics.solver.newton_iterations,
                                         statistics.solver.step_error);
            return statistics;
          }

        // Rejected: the particles are untouched; halve dt and retry.
        ++rejected;
        // The retry starts from the last step's contact status again: a
        // status decided afresh at a long step, on v^n + dt f / m, catches
        // and releases thousands of slots, and the retry fails too. The
        // status is dropped where it may be what leads the solve astray (a
        // fast impact at a long step): when the residual with it was not
        // finite at the first iterate, and after two failed solves. A solve
        // that converged and was rejected for its accuracy does not count.
        if (!statistics.solver.rejected_for_accuracy)
          ++failed_solves;
        if (HeldContactStatus<dim> *held = stepper->get_held_contact_status();
            held != nullptr &&
            (failed_solves >= 2 || statistics.solver.failed_at_first_iterate))
          held->clear();
        const double failed_step = time.get_next_step_size();
        pcout << "  step " << step_offset + time.get_step_number() + 1
              << " at t = " << time.get_current_time()
              << " rejected with dt = " << failed_step << ": "
              << statistics.solver.failure << std::endl;
        // Below the explicit stable step (or the minimum step) a step that
        // is not grown beyond the nominal one is advanced explicitly if the
        // run allows it; a grown one is retried at half its length first.
        const bool below_explicit_step =
          fallback && !time_step_controller->is_grown(failed_step) &&
          0.5 * failed_step < fallback->stable_step(particle_handler);
        if (below_explicit_step || !time_step_controller->reject(failed_step))
          {
            if (fallback)
              return advance_explicitly(time, rejected);
            write_output(step_offset + time.get_step_number(),
                         time.get_current_time(),
                         time.get_previous_step_size(),
                         schedule.extra_output_written());
            const bool adaptive =
              parameters.time_stepping.adaptive_time_stepping;
            std::ostringstream message;
            message << "the implicit step from t = " << time.get_current_time()
                    << " failed with dt = " << failed_step << " ("
                    << statistics.solver.failure << ") and "
                    << (adaptive ?
                          "halving it would go below the minimum time step " +
                            std::to_string(
                              time_step_controller->get_minimum_step()) :
                          std::string("adaptive time stepping is off"))
                    << ". Lower Time stepping/CFL number or Time step, "
                    << (adaptive ? "set Time stepping/Explicit fallback = "
                                   "true, " :
                                   "")
                    << "or raise Nonlinear solver/Maximum Newton iterations.";
            throw InputError(adaptive ? "Time stepping/Minimum time step" :
                                        "Time stepping/Adaptive time stepping",
                             message.str());
          }
        time.set_desired_next_step_size(time_step_controller->retry_step());
      }
  }



  template <int dim>
  StepStatistics
  Simulator<dim>::advance_explicitly(const DiscreteTime &time,
                                     const unsigned int  rejected)
  {
    StepStatistics statistics;
    {
      TimerOutput::Scope scope(timer, "explicit fallback");
      statistics = fallback->advance(particle_handler,
                                     time.get_current_time(),
                                     time.get_next_step_size());
    }
    statistics.solver.rejected = rejected;
    last_stepper               = fallback.get();
    // The contact status of the last implicit step does not describe the
    // state after the sub-steps: the next implicit step decides afresh.
    if (HeldContactStatus<dim> *held = stepper->get_held_contact_status())
      held->clear();
    if (StepErrorEstimator<dim> *estimator =
          stepper->get_step_error_estimator())
      estimator->forget();
    if (bool *quasi_static = stepper->get_quasi_static_flag())
      *quasi_static = false;
    time_step_controller->resume_after_fallback(time.get_next_step_size());
    pcout << "  step " << step_offset + time.get_step_number() + 1
          << " at t = " << time.get_current_time() << " advanced by "
          << statistics.solver.explicit_substeps
          << " explicit sub-steps over dt = " << time.get_next_step_size()
          << " (Time stepping/Explicit fallback)" << std::endl;
    return statistics;
  }



  template StepStatistics
  Simulator<2>::advance_one_step(DiscreteTime &);
  template StepStatistics
  Simulator<3>::advance_one_step(DiscreteTime &);
} // namespace grainmpm
