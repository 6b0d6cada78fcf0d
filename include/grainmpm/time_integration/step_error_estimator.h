// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_step_error_estimator_h
#define grainmpm_time_integration_step_error_estimator_h

#include <grainmpm/base/config.h>
#include <grainmpm/particles/grain_generator.h>

#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace grainmpm
{
  /**
   * The local error of an implicit step, estimated from the change of the
   * material points' accelerations from one step to the next, after
   * Zienkiewicz & Xie (Earthquake Engineering and Structural Dynamics
   * 20 (1991) 871-887). For the trapezoidal rule (theta = 1/2) the error
   * of the displacement of a step of length dt is e = dt^2 / 12 (a^{n+1}
   * - a^n); the estimate takes the acceleration of each deformable point
   * over a step, a = (v^{n+1} - v^n) / dt, and its change from the last
   * step, scaled to one step of length dt, and measures e against the
   * displacement of the step, in the mass-weighted norm:
   *
   *   eta^2 = sum_p m_p |dt^2 / 12 Delta a_p|^2 / sum_p m_p |dt vbar_p|^2,
   *
   * Delta a_p = (a_p - a_p^last) 2 dt / (dt + dt^last), vbar_p the mean of
   * the point's velocities at both ends of the step. Each point keeps its
   * acceleration of the last step with its other properties
   * (MaterialPointLayout::acceleration), so that the estimate follows
   * points between MPI ranks and into checkpoints.
   *
   * Use: record_velocities() before the points get their new velocities,
   * estimate() after, before they are sorted into cells again (both walk
   * the points in the same order).
   */
  template <int dim>
  class StepErrorEstimator
  {
  public:
    /** @p grains says which grains are rigid (their points are left out). */
    explicit StepErrorEstimator(const std::vector<GrainInfo<dim>> &grains);

    /** Keep the velocities v^n of the points of this rank. */
    void
    record_velocities(const Particles::ParticleHandler<dim> &particle_handler);

    /**
     * Store each point's acceleration over the step of length @p dt and
     * return eta (collective over @p communicator), or -1 if there is no
     * estimate: the first step of a run or after forget(), or no point
     * moved.
     */
    double
    estimate(Particles::ParticleHandler<dim> &particle_handler,
             const double                     dt,
             const MPI_Comm                   communicator);

    /**
     * The stored accelerations do not belong to the last step (it was
     * advanced otherwise, e.g. by explicit sub-steps): the next step has
     * no estimate.
     */
    void
    forget()
    {
      last_step = 0.;
    }

    /** Write or read the length of the last step (for checkpoints). */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &last_step;
    }

  private:
    /** For each grain: its points count (not rigid). */
    std::vector<bool> deformable;

    /** v^n of this rank's points, in the order of the handler. */
    std::vector<Tensor<1, dim>> velocities;

    /** The step whose accelerations the points hold; 0: none. */
    double last_step = 0.;
  };
} // namespace grainmpm

#endif
