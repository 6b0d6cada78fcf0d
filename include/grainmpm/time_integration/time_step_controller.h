// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_time_step_controller_h
#define grainmpm_time_integration_time_step_controller_h

#include <grainmpm/base/parameters.h>

#include <limits>

namespace grainmpm
{
  /**
   * The nominal step of @p parameters: the fixed `Time step`, or
   * dt = CFL h / (c + |v|_max) with @p minimum_cell_size h, @p wave_speed c
   * (the largest dilatational wave speed) and @p max_speed |v|_max.
   */
  double
  nominal_time_step(const TimeSteppingParameters &parameters,
                    const double                  minimum_cell_size,
                    const double                  wave_speed,
                    const double                  max_speed);



  /**
   * The size of the time steps: from the CFL condition
   * dt = CFL h_min / (c_max + |v|_max) or the fixed `Time step`, and the
   * failure policy of the implicit scheme: a rejected step is retried with
   * half the step (down to `Minimum time step`), and a cut step grows
   * back by min(2, N_t / N) after `Steps before growth` consecutive easy
   * steps, N the Newton iterations of the step and N_t half of those
   * allowed (easy: N <= N_t). With `Maximum time step` above the nominal
   * step (that of `Time step` or `CFL number`) the steps go on growing by
   * the same rule beyond it, up to that maximum and to the step in which
   * the fastest grain moves `Maximum displacement per step` cells (never
   * below the nominal step). Its state is written to checkpoints by
   * serialize(). A case whose End time needs more than
   * maximum_steps_to_end steps is refused when the controller is made.
   */
  class TimeStepController
  {
  public:
    /** The most steps a run may need to reach its End time. */
    static constexpr double maximum_steps_to_end = 1e9;

    /**
     * @p minimum_cell_size and @p wave_speed (the largest dilatational
     * wave speed) set the CFL step; @p max_newton_iterations tells an easy
     * step.
     */
    TimeStepController(const TimeSteppingParameters &parameters,
                       const unsigned int            max_newton_iterations,
                       const double                  minimum_cell_size,
                       const double                  wave_speed);

    /**
     * The first step of a run whose particles move at most at
     * @p max_speed; also sets the minimum step (`Minimum time step`, or
     * 1/1024 of the first step).
     */
    double
    first_step(const double max_speed);

    /**
     * A step of size @p failed_step was rejected: halve it. Returns false
     * if no retry is allowed (adaptive time stepping off, or the half step
     * below the minimum step).
     */
    bool
    reject(const double failed_step);

    /**
     * A step of size @p failed_step was advanced by explicit sub-steps
     * after the implicit solve failed on it: the implicit steps resume
     * with that step and grow back as after a cut.
     */
    void
    resume_after_fallback(const double failed_step);

    /** The step to retry a rejected step with. */
    double
    retry_step() const
    {
      return step_limit;
    }

    /**
     * An implicit step of size @p step was accepted after
     * @p newton_iterations: count it towards growing a cut step back. With
     * growth beyond the nominal step and a Step error tolerance, its
     * estimated relative error @p step_error (StepErrorEstimator; negative:
     * none) bounds the next step to step sqrt(tolerance / step_error),
     * between half and twice the step, and not below the nominal step.
     */
    void
    accept(const double       step,
           const unsigned int newton_iterations,
           const double       step_error = -1.);

    /**
     * The step after an accepted one in which particles moved at most at
     * @p max_speed: the CFL (or fixed) step, limited by a cut step as long
     * as that is smaller; with growth beyond it, the grown step, limited
     * by the largest step and the displacement bound on the grains moving
     * at most at @p grain_speed (their rigid-body motion; negative: take
     * @p max_speed).
     */
    double
    next_step(const double max_speed, const double grain_speed = -1.);

    /**
     * Whether next_step() bounds grown steps by the speed of the grains
     * (growth beyond the nominal step and a Maximum displacement per
     * step).
     */
    bool
    needs_grain_speed() const
    {
      return maximum_step > 0. && parameters.maximum_displacement > 0.;
    }

    /** The smallest step at which a retry was made (0 if none). */
    double
    smallest_step_tried() const
    {
      return smallest_step < std::numeric_limits<double>::max() ?
               smallest_step :
               0.;
    }

    /**
     * Whether @p step is longer than the nominal step of the material at
     * rest: a step grown beyond it (a step cut and grown back to it may
     * exceed it by a round-off). A rejected grown step is retried
     * implicitly with half its length, also where that is below the
     * explicit stable step (a CFL number below 1); the explicit fallback
     * takes only steps that are not grown.
     */
    bool
    is_grown(const double step) const
    {
      return step > (1. + 1e-9) * cfl_step(0.);
    }

    /** The smallest step the failure policy may try. */
    double
    get_minimum_step() const
    {
      return minimum_step;
    }

    /** Read or write the state with @p archive. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &minimum_step &step_limit &easy_steps &smallest_step;
      archive                                       &accuracy_limit;
    }

  private:
    /** The CFL (or fixed) step for particles moving at @p max_speed. */
    double
    cfl_step(const double max_speed) const;

    /**
     * The largest step after one in which the grains moved at most at
     * @p grain_speed, given the nominal step @p nominal: @p nominal without
     * growth, else the maximum time step, the displacement bound and the
     * bound of the error estimate, not below @p nominal; @p nominal if the
     * displacement bound allows less than twice it.
     */
    double
    largest_step(const double nominal, const double grain_speed) const;

    const TimeSteppingParameters &parameters;
    const unsigned int            max_newton_iterations;
    const double                  minimum_cell_size;
    const double                  wave_speed;
    /**
     * The largest step (TimeSteppingParameters::largest_time_step() on
     * these cells and wave speed); 0 without growth.
     */
    const double maximum_step;

    double minimum_step = 0.;
    /** A cut or grown step (0 if none). */
    double       step_limit    = 0.;
    unsigned int easy_steps    = 0;
    double       smallest_step = std::numeric_limits<double>::max();
    /** The bound of the error estimate on the next step (0 if none). */
    double accuracy_limit = 0.;
  };
} // namespace grainmpm

#endif
