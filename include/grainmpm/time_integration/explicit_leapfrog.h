// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_explicit_leapfrog_h
#define grainmpm_time_integration_explicit_leapfrog_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  using namespace dealii;

  /**
   * What one step did.
   */
  struct StepStatistics
  {
    /** Contact nodes where the projection corrected a field. */
    unsigned int n_contact_nodes = 0;
    /** Particles removed through open faces in this step. */
    types::particle_index n_removed = 0;
    /** Largest particle speed after the step. */
    double max_speed = 0.;
    /** True if some particle changed cells and the handler was sorted. */
    bool sorted = false;
  };

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
  class ExplicitLeapfrog
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    ExplicitLeapfrog(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    /**
     * Advance the particles of @p particle_handler from @p time by @p dt.
     * Throws InputError if a particle leaves the grid through a closed face.
     */
    StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt);

    /** The slot layout of the last step. */
    const GrainFieldLayout<dim> &
    get_layout() const
    {
      return layout;
    }

    /** Slot masses of the last step. */
    const VectorType &
    get_masses() const
    {
      return masses;
    }

    /** Slot velocities at the end of the last step (v^L). */
    const VectorType &
    get_velocities() const
    {
      return velocities_new;
    }

    /** 1 for nodes where contact corrected a field in the last step. */
    const std::vector<unsigned char> &
    get_node_contact_flags() const
    {
      return node_in_contact;
    }

  private:
    /** Mass, momentum and mass gradient per slot; v^n = p/m. */
    void
    particles_to_grid(Particles::ParticleHandler<dim> &particle_handler,
                      const double                     time);

    /**
     * Strain increment dt grad v from @p grid_velocities, new stress,
     * deformation gradient and volume of every deformable particle.
     */
    void
    update_stresses(Particles::ParticleHandler<dim> &particle_handler,
                    const VectorType                &grid_velocities,
                    const double                     dt);

    /** Internal force -V sigma . grad S and gravity m g S per slot. */
    void
    compute_forces(Particles::ParticleHandler<dim> &particle_handler);

    /** v^L = v + dt f / m on deformable slots; rigid slots prescribed. */
    void
    integrate_grid_velocities(const double dt);

    /** Contact and walls on @p velocities. */
    unsigned int
    apply_constraints(VectorType &velocities);

    /** v = p / m on slots with mass, zero elsewhere. */
    void
    velocities_from_momenta(VectorType &velocities) const;

    /** Set the slots of rigid fields to their prescribed velocity. */
    void
    prescribe_rigid_velocities(VectorType &velocities, const double time) const;

    /**
     * FLIP/PIC velocity and position update; records particles that left
     * through open faces and whether the handler needs sorting.
     */
    void
    grid_to_particles(Particles::ParticleHandler<dim> &particle_handler,
                      const double                     time,
                      const double                     dt,
                      StepStatistics                  &statistics);

    /** Velocities remapped from the particle momenta (MUSL). */
    void
    remap_velocities(Particles::ParticleHandler<dim> &particle_handler);

    const Parameters<dim>                                      &parameters;
    const BackgroundGrid<dim>                                  &grid;
    const std::vector<GrainInfo<dim>>                          &grains;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;

    std::vector<unsigned int> field_of_grain;
    std::vector<bool>         field_is_rigid;
    GrainContact<dim>         contact;
    TransferCache<dim>        cache;
    GrainFieldLayout<dim>     layout;

    VectorType masses;
    VectorType momenta;
    VectorType mass_gradients;
    VectorType normals;
    VectorType forces;
    /** v^n from P2G (uncorrected): the FLIP reference. */
    VectorType velocities_p2g;
    /** v^n after contact and walls (USF strain velocity). */
    VectorType velocities_old;
    /** v^L after contact and walls. */
    VectorType velocities_new;

    std::vector<unsigned char> node_in_contact;
    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      particles_to_remove;
  };
} // namespace grainmpm

#endif
