// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_explicit_fallback_h
#define grainmpm_time_integration_explicit_fallback_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/time_integration/explicit_leapfrog.h>

#include <memory>

namespace grainmpm
{
  /**
   * The explicit fallback of the implicit scheme (`Time stepping/Explicit
   * fallback`): advance() takes an interval that the implicit solve could
   * not, by explicit leapfrog sub-steps of a quarter of the stable step
   * h_min / (c_max + |v|_max), with the run's contact law and transfer and
   * the update-stress-last order (whose contact reactions do no work on
   * the strain) on the lumped mass. The grid of the interval (for output)
   * is that of its last sub-step; its constraint impulses are the sum over
   * the sub-steps, so that the reaction forces written for the interval
   * are their means over it, as for any other step.
   */
  template <int dim>
  class ExplicitFallback : public TimeIntegrator<dim>
  {
  public:
    /**
     * The run's @p parameters (copied, with the explicit settings above),
     * grid, grains and materials.
     */
    ExplicitFallback(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    /**
     * The stable step of the explicit leapfrog for the particles of
     * @p particle_handler as they move now. Collective.
     */
    double
    stable_step(const Particles::ParticleHandler<dim> &particle_handler) const;

    /**
     * Advance from @p time over @p interval by sub-steps. The statistics
     * add up those of the sub-steps, with their number in
     * SolverCounts::explicit_substeps.
     */
    StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     interval) override;

    const GrainFieldLayout<dim> &
    get_layout() const override
    {
      return leapfrog->get_layout();
    }

    const GridState<dim> &
    get_grid_state() const override
    {
      return leapfrog->get_grid_state();
    }

    const ConstraintImpulses<dim> &
    get_impulses() const override
    {
      return impulses;
    }

  private:
    const Parameters<dim>                  parameters;
    const MPI_Comm                         communicator;
    const double                           minimum_cell_size;
    const double                           wave_speed;
    std::unique_ptr<ExplicitLeapfrog<dim>> leapfrog;
    /** The constraint impulses summed over the sub-steps. */
    ConstraintImpulses<dim> impulses;
  };
} // namespace grainmpm

#endif
