// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_time_integrator_h
#define grainmpm_time_integration_time_integrator_h

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
#include <string>
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
    /**
     * Deformable particles put back on a closed face that the interpolated
     * velocity had carried less than half a cell through.
     */
    types::particle_index n_held_at_walls = 0;
    /** Largest particle speed after the step. */
    double max_speed = 0.;
    /** True if some particle changed cells and the handler was sorted. */
    bool sorted = false;

    /** False if an implicit step failed; the particles are then untouched. */
    bool converged = true;
    /** Why an implicit step failed. */
    std::string failure;
    /** Newton iterations of the accepted solve. */
    unsigned int newton_iterations = 0;
    /** Krylov iterations summed over the Newton iterations. */
    unsigned int linear_iterations = 0;
    /** Residual evaluations of the step (all attempts). */
    unsigned int residual_evaluations = 0;
    /** Final RMS(R) / U of the accepted solve (U: velocity scale). */
    double residual_norm = 0.;
    /** Changes of the contact status during the accepted solve. */
    unsigned int status_changes = 0;
    /**
     * Implicit scheme: change of the grid energy 1/2 sum m v^2 + sum V W
     * of the deformable grains over the step, from the particle-to-grid
     * velocities (so including the contact pass on v^n) to the end
     * velocities: the time integrator's share of the energy balance. With
     * transfer_energy_change it adds up to the change of the particles'
     * kinetic plus elastic energy (without gravity and removed particles).
     */
    double grid_energy_change = 0.;
    /**
     * Both schemes: what the grid-to-particle velocity update adds to the
     * kinetic energy of the deformable particles beyond the change of the
     * grid kinetic energy it maps, sum_p 1/2 m_p |v_p|^2 (after - before)
     * - sum_s 1/2 m_s (|v_s^new|^2 - |v_s^p2g|^2). For FLIP it is
     * -1/2 (sum_s m_s |dv_s|^2 - sum_p m_p |sum_s S_sp dv_s|^2) <= 0: the
     * lumped-mass loss of Cummins & Brackbill, which the grid cannot see.
     */
    double transfer_energy_change = 0.;
    /**
     * Both schemes: the step's plastic work sum_p V_p sigma : de_p of the
     * deformable particles (>= 0).
     */
    double plastic_work = 0.;
    /**
     * Both schemes: the work the contact, wall and rigid-grain constraints
     * of the step do on the deformable grains, split into what rigid grains
     * and walls put in (boundary_work: the reaction on the slots of a node
     * times the velocity of its rigid partner; walls are at rest) and what
     * friction takes out (friction_work >= 0 with Coulomb friction, 0 for
     * frictionless constraints). The reaction on a slot is m_s times the
     * change the constraints make to its end velocity; it works on the
     * velocity that moves the particles (v^theta implicit, v^{n+1}
     * explicit).
     */
    double friction_work = 0.;
    double boundary_work = 0.;
    /** Attempts rejected before this step was accepted. */
    unsigned int rejected = 0;

    /**
     * Add up (largest speed: maximum; sorted: or) what each rank counted
     * of its particles and slots: contact nodes, removed and held points,
     * the transfer energy change and the plastic, friction and boundary
     * work. Collective.
     */
    void
    reduce(const MPI_Comm communicator);
  };



  /**
   * The largest dilatational wave speed of the materials of the deformable
   * grains (0 if there are none).
   */
  template <int dim>
  double
  largest_wave_speed(
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);



  /**
   * What the explicit and the implicit step share: the per-step transfer
   * cache and slot layout, particle-to-grid transfer of mass, momentum and
   * mass gradient, the contact normals, contact and walls, rigid grains,
   * and the particle update with its checks of particles leaving the box.
   * A derived class implements advance().
   */
  template <int dim>
  class TimeIntegrator
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    TimeIntegrator(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    virtual ~TimeIntegrator() = default;

    /**
     * Advance the particles of @p particle_handler from @p time by @p dt.
     * Throws InputError if a particle leaves the grid through a closed face.
     * An implicit step that fails returns `converged == false` and leaves
     * the particles untouched.
     */
    virtual StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt) = 0;

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

    /** Slot velocities at the end of the last step. */
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

  protected:
    /**
     * Cache and layout for the positions at @p time, P2G, contact normals.
     */
    void
    begin_step(Particles::ParticleHandler<dim> &particle_handler,
               const double                     time);

    /** Mass, momentum and mass gradient per slot; v^n = p/m. */
    void
    particles_to_grid(Particles::ParticleHandler<dim> &particle_handler,
                      const double                     time);

    /** Contact and walls on @p velocities. */
    unsigned int
    apply_constraints(VectorType &velocities);

    /** v = p / m on slots with mass, zero elsewhere. */
    void
    velocities_from_momenta(VectorType &velocities) const;

    /**
     * Add the work of the constraints that changed @p before into
     * @p after, on the velocities @p rate, to @p statistics
     * (StepStatistics::friction_work and boundary_work).
     */
    void
    add_constraint_work(const VectorType &before,
                        const VectorType &after,
                        const VectorType &rate,
                        StepStatistics   &statistics) const;

    /** Set the slots of rigid fields to their prescribed velocity. */
    void
    prescribe_rigid_velocities(VectorType &velocities, const double time) const;

    /**
     * FLIP/PIC velocity update from `velocities_new` (the increment
     * measured from `velocities_p2g`) and position update
     * x += dt sum_i S_ip v_i with v = @p position_velocities; records
     * particles that left through open faces and whether the handler needs
     * sorting.
     */
    void
    grid_to_particles(Particles::ParticleHandler<dim> &particle_handler,
                      const VectorType                &position_velocities,
                      const double                     time,
                      const double                     dt,
                      StepStatistics                  &statistics);

    /**
     * Store the new @p stress and @p plastic_strain of a particle with
     * @p properties, update its deformation gradient by the increment
     * @p increment (dt grad v: F <- (I + dt grad v) F) and its volume
     * det(F) V_0. Returns the new volume.
     */
    static double
    store_particle_state(const ArrayView<double>     &properties,
                         const SymmetricTensor<2, 3> &stress,
                         const double                 plastic_strain,
                         const Tensor<2, dim>        &increment);

    /** Remove particles that left, sort if needed. */
    void
    finish_step(Particles::ParticleHandler<dim> &particle_handler,
                StepStatistics                  &statistics);

    const Parameters<dim>                                      &parameters;
    const BackgroundGrid<dim>                                  &grid;
    const std::vector<GrainInfo<dim>>                          &grains;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;

    std::vector<unsigned int> field_of_grain;
    std::vector<bool>         field_is_rigid;
    bool                      has_rigid_fields = false;
    GrainContact<dim>         contact;
    TransferCache<dim>        cache;
    GrainFieldLayout<dim>     layout;

    VectorType masses;
    VectorType momenta;
    VectorType mass_gradients;
    VectorType normals;
    /** v^n from P2G (uncorrected): the FLIP reference. */
    VectorType velocities_p2g;
    /** The grid velocity at the end of the step. */
    VectorType velocities_new;

    std::vector<unsigned char> node_in_contact;
    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      particles_to_remove;
  };
} // namespace grainmpm

#endif
