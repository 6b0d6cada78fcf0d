// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_explicit_leapfrog_h
#define grainmpm_time_integration_explicit_leapfrog_h

#include <grainmpm/base/config.h>
#include <grainmpm/time_integration/time_integrator.h>

namespace grainmpm
{
  /**
   * The explicit leapfrog step of Cummins & Brackbill (2001), eqs. (7)-(10),
   * on the multi-grain grid field, with Bardenhagen-Brackbill-Sulsky
   * contact and box walls.
   *
   * USF (default, eqs. 8-10 as written): P2G of mass and momentum,
   * contact and walls on v^n, stress/volume update from the corrected v^n,
   * forces from the new stress, v^L = v^n + dt f/m, contact and walls on v^L,
   * G2P. MUSL: forces from the old stress, v^L, contact, walls, G2P, then
   * the stress update from the grid velocity remapped from the new particle
   * momenta (with contact and walls again). USL: as MUSL, but the stress
   * update from v^{n+1} itself, the constrained grid velocity that moved
   * the particles; then the strain and the motion see the same
   * constraints, and a reaction does no work on the strain (with USF the
   * constraints on v^n and on v^L differ, and a grain resting on a wall
   * under gravity slowly gains energy).
   *
   * The FLIP increment is measured from the uncorrected P2G velocity, so
   * that the particles receive the full contact impulse and the total
   * momentum is conserved through contact.
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

    const GrainFieldLayout<dim> &
    get_layout() const override
    {
      return transfer.get_layout();
    }

    const GridState<dim> &
    get_grid_state() const override
    {
      return state;
    }

    /** Where the contact locates the rigid grains. */
    RigidGrainMotion<dim> *
    get_rigid_grain_motion() override
    {
      return &transfer.get_rigid_motion();
    }

  private:
    /**
     * Contact and walls on @p velocities; returns the contact nodes. With
     * @p record, the impulses go into the step's GridState::impulses (the
     * velocity changes that the particles receive).
     */
    unsigned int
    apply_constraints(VectorType &velocities, const bool record);

    /** v^L = v + dt f / m on deformable slots whose mass is not round-off. */
    void
    integrate_grid_velocities(const double dt);

    const Parameters<dim> &parameters;
    Transfer<dim>          transfer;
    GrainContact<dim>      contact;
    GridState<dim>         state;

    VectorType forces;
    /** The end velocities before the constraints (for their work). */
    VectorType unconstrained_velocities;
    /** v^n after contact and walls (USF strain velocity). */
    VectorType velocities_old;
  };
} // namespace grainmpm

#endif
