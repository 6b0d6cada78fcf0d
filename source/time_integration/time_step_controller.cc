// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/time_integration/time_step_controller.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace grainmpm
{
  TimeStepController::TimeStepController(
    const TimeSteppingParameters &parameters,
    const unsigned int            max_newton_iterations,
    const double                  minimum_cell_size,
    const double                  wave_speed)
    : parameters(parameters)
    , max_newton_iterations(max_newton_iterations)
    , minimum_cell_size(minimum_cell_size)
    , wave_speed(wave_speed)
    , maximum_step(parameters.largest_time_step(minimum_cell_size, wave_speed))
  {
    const double limit = minimum_cell_size / wave_speed;
    if (parameters.scheme == TimeSteppingScheme::explicit_leapfrog &&
        parameters.time_step > limit)
      {
        std::ostringstream entry, message;
        entry << "Time stepping/Time step = " << parameters.time_step;
        message
          << "is above the stability limit of the explicit leapfrog, h / c = "
          << limit
          << " (h the smallest cell size, c the largest dilatational wave "
             "speed of the materials): its energy grows without bound. Use "
             "at most that (a quarter of it is typical), Time step = 0 with "
             "a CFL number, or Scheme = implicit theta.";
        throw InputError(entry.str(), message.str());
      }

    // A run that cannot end: refused with the numbers instead of stepping
    // for ever (the CFL step with the material at rest is an upper bound,
    // so this is a lower bound of the number of steps).
    const double step    = cfl_step(0.);
    const double n_steps = parameters.end_time / step;
    if (!(n_steps <= maximum_steps_to_end))
      {
        std::ostringstream entry, message;
        if (parameters.time_step > 0.)
          entry << "Time stepping/Time step = " << parameters.time_step;
        else
          entry << "Time stepping/CFL number = " << parameters.cfl_number;
        message << "End time = " << parameters.end_time << " needs at least "
                << n_steps << " steps of dt = " << step
                << " (h = " << minimum_cell_size << ", c = " << wave_speed
                << "), more than the " << maximum_steps_to_end
                << " steps a run may take. Use a larger time step or a "
                   "shorter End time.";
        throw InputError(entry.str(), message.str());
      }
  }



  double
  nominal_time_step(const TimeSteppingParameters &parameters,
                    const double                  minimum_cell_size,
                    const double                  wave_speed,
                    const double                  max_speed)
  {
    if (parameters.time_step > 0.)
      return parameters.time_step;
    return parameters.cfl_number * minimum_cell_size / (wave_speed + max_speed);
  }



  double
  TimeStepController::cfl_step(const double max_speed) const
  {
    return nominal_time_step(parameters,
                             minimum_cell_size,
                             wave_speed,
                             max_speed);
  }



  double
  TimeStepController::first_step(const double max_speed)
  {
    const double step = cfl_step(max_speed);
    minimum_step      = parameters.minimum_time_step > 0. ?
                          parameters.minimum_time_step :
                          step / 1024.;
    return step;
  }



  bool
  TimeStepController::reject(const double failed_step)
  {
    if (!parameters.adaptive_time_stepping || 0.5 * failed_step < minimum_step)
      return false;
    step_limit    = 0.5 * failed_step;
    easy_steps    = 0;
    smallest_step = std::min(smallest_step, step_limit);
    return true;
  }



  void
  TimeStepController::resume_after_fallback(const double failed_step)
  {
    step_limit    = failed_step;
    easy_steps    = 0;
    smallest_step = std::min(smallest_step, failed_step);
  }



  void
  TimeStepController::accept(const double       step,
                             const unsigned int newton_iterations,
                             const double       step_error)
  {
    // The error estimate of a step of length dt goes as dt^2 where the
    // motion is smooth (Zienkiewicz & Xie): the step that meets the
    // tolerance, within a factor of two of this one.
    if (maximum_step > 0. && parameters.step_error_tolerance > 0. &&
        step_error >= 0.)
      accuracy_limit =
        step_error > 0. ?
          step *
            std::clamp(std::sqrt(parameters.step_error_tolerance / step_error),
                       0.5,
                       2.) :
          2. * step;
    // A cut step grows back by min(2, N_t / N), N_t half the Newton
    // iterations allowed, after Steps before growth easy steps (N <= N_t);
    // with a Maximum time step any step grows so (next_step() bounds it).
    // (Shrinking the next step after a hard one, N > N_t, was tried: where
    // N does not fall with dt, e.g. at most 3 iterations allowed and 2 or 3
    // needed, it shrank the step without end.)
    const double target  = 0.5 * max_newton_iterations;
    const double n       = std::max(1U, newton_iterations);
    const bool   growing = step_limit > 0. || maximum_step > 0.;
    if (growing && n <= target)
      {
        if (++easy_steps >= parameters.steps_before_growth)
          {
            step_limit = std::max(step_limit, step) * std::min(2., target / n);
            easy_steps = 0;
          }
      }
    else
      easy_steps = 0;
  }



  double
  TimeStepController::largest_step(const double nominal,
                                   const double grain_speed) const
  {
    if (!(maximum_step > nominal))
      return nominal;
    double largest = maximum_step;
    if (parameters.maximum_displacement > 0. && grain_speed > 0.)
      {
        // Grains that move so fast that the displacement bound allows less
        // than twice the nominal step (grains in flight at a few per cent of
        // the wave speed) keep the nominal step: a step a quarter longer
        // into their impacts gains nothing and brings the energy bound's
        // rejections.
        const double bound =
          parameters.maximum_displacement * minimum_cell_size / grain_speed;
        if (bound < 2. * nominal)
          return nominal;
        largest = std::min(largest, bound);
      }
    if (accuracy_limit > 0.)
      largest = std::min(largest, accuracy_limit);
    return std::max(largest, nominal);
  }



  double
  TimeStepController::next_step(const double max_speed,
                                const double grain_speed)
  {
    const double nominal = cfl_step(max_speed);
    if (step_limit == 0.)
      return nominal;
    const double largest =
      largest_step(nominal, grain_speed < 0. ? max_speed : grain_speed);
    if (step_limit < largest)
      return step_limit;
    // At the largest step a cut step has grown back; a grown one is held
    // there, so that it grows again from it, not from a step the bounds
    // no longer allow.
    step_limit = largest > nominal ? largest : 0.;
    return largest;
  }
} // namespace grainmpm
