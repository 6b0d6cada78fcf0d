// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_explicit_leapfrog_h
#define grainmpm_time_integration_explicit_leapfrog_h

#include <grainmpm/time_integration/time_integrator.h>

namespace grainmpm
{
  using namespace dealii;

  /**
   * The explicit leapfrog step of seed eqs. (7)-(10) on the multi-grain
   * grid field, with Bardenhagen-Brackbill-Sulsky contact and box walls.
   *
   * USF (default, eqs. 8-10 as written): P2G of mass and momentum,
   * contact and walls on v^n, stress/volume update from the corrected v^n,
   * forces from the new stress, v^L = v^n + dt f/m, contact and walls on v^L,
   * G2P. MUSL: forces from the old stress, v^L, contact, walls, G2P, then
   * the stress update from the grid velocity remapped from the new particle
   * momenta (with contact and walls again).
   *
   * The FLIP increment is measured from the uncorrected P2G velocity, so
   * that the particles receive the full contact impulse (momentum-consistent
   * choice of reference/physics.md section 3.7).
   */
  template <int dim>
  class ExplicitLeapfrog : public TimeIntegrator<dim>
  {
  public:
    using VectorType = typename TimeIntegrator<dim>::VectorType;

    ExplicitLeapfrog(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt) override;

  private:
    /**
     * Strain increment dt grad v from @p grid_velocities, new stress,
     * deformation gradient and volume of every deformable particle; adds
     * the plastic work to @p plastic_work.
     */
    void
    update_stresses(Particles::ParticleHandler<dim> &particle_handler,
                    const VectorType                &grid_velocities,
                    const double                     dt,
                    double                          &plastic_work);

    /** Internal force -V sigma . grad S and gravity m g S per slot. */
    void
    compute_forces(Particles::ParticleHandler<dim> &particle_handler);

    /** v^L = v + dt f / m on deformable slots; rigid slots prescribed. */
    void
    integrate_grid_velocities(const double dt);

    /** Velocities remapped from the particle momenta (MUSL). */
    void
    remap_velocities(Particles::ParticleHandler<dim> &particle_handler);

    using TimeIntegrator<dim>::parameters;
    using TimeIntegrator<dim>::grid;
    using TimeIntegrator<dim>::grains;
    using TimeIntegrator<dim>::materials;
    using TimeIntegrator<dim>::field_is_rigid;
    using TimeIntegrator<dim>::cache;
    using TimeIntegrator<dim>::layout;
    using TimeIntegrator<dim>::masses;
    using TimeIntegrator<dim>::momenta;
    using TimeIntegrator<dim>::velocities_p2g;
    using TimeIntegrator<dim>::velocities_new;
    using TimeIntegrator<dim>::apply_constraints;
    using TimeIntegrator<dim>::prescribe_rigid_velocities;
    using TimeIntegrator<dim>::velocities_from_momenta;

    VectorType forces;
    /** The end velocities before the constraints (for their work). */
    VectorType unconstrained_velocities;
    /** v^n after contact and walls (USF strain velocity). */
    VectorType velocities_old;
  };
} // namespace grainmpm

#endif
