// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_transfer_h
#define grainmpm_transfer_transfer_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/base/step_statistics.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/particle_update_check.h>
#include <grainmpm/transfer/rigid_grain_motion.h>
#include <grainmpm/transfer/transfer_cache.h>
#include <grainmpm/transfer/transfer_options.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  template <int dim>
  class MassMatrix;

  /**
   * The particle-grid transfer of one step: the single place where the
   * shape functions (`Material points/Shape functions`: linear, uGIMP or
   * cpGIMP) are evaluated (TransferCache::reinit) and where the particle
   * loops of both time integrators live.
   *
   * reinit() evaluates the kernel at the particle positions at the start
   * of the step and builds the multi-valued grid layout (the slots);
   * everything else uses the cached values S_ip and grad S_ip:
   * - particle to grid: mass m_s = sum_p m_p S_ip, momentum
   *   p_s = sum_p m_p v_p S_ip and mass gradient sum_p m_p grad S_ip per
   *   slot (the particles of the slot's field);
   * - the velocity gradient of a particle, sum_i v_i (x) grad S_ip, and the
   *   internal force -sum_p V_p sigma_p . grad S_ip it gives back;
   * - the constitutive update of the particles from a grid velocity;
   * - grid to particle: FLIP/PIC velocity and position update, with the
   *   checks of particles leaving the box.
   *
   * Grid vectors have `dim` numbers per slot (slot * dim + d), laid out by
   * get_layout().
   */
  template <int dim>
  class Transfer
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * Every grain has its own velocity field, except with `Contact model =
     * none`, where all deformable grains share the field of the first of
     * them.
     */
    Transfer(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
      const TransferOptions &options = TransferOptions());

    /**
     * Evaluate the shape functions at the positions of the particles of
     * @p particle_handler and build the slot layout. Collective.
     */
    void
    reinit(const Particles::ParticleHandler<dim> &particle_handler);

    /** The slot layout of the last reinit(). */
    const GrainFieldLayout<dim> &
    get_layout() const
    {
      return layout;
    }

    /** The cached kernel values of the last reinit(). */
    const TransferCache<dim> &
    get_cache() const
    {
      return cache;
    }

    /** The grains. */
    const std::vector<GrainInfo<dim>> &
    get_grains() const
    {
      return grains;
    }

    /** The motion of the rigid grains. */
    const RigidGrainMotion<dim> &
    get_rigid_motion() const
    {
      return rigid_motion;
    }

    /** The motion of the rigid grains, to write or read it (checkpoints). */
    RigidGrainMotion<dim> &
    get_rigid_motion()
    {
      return rigid_motion;
    }

    /**
     * Locate the rigid grains at @p time, the start of a step of @p dt,
     * (RigidGrainMotion::locate()). Collective.
     */
    void
    locate_rigid_grains(const Particles::ParticleHandler<dim> &particle_handler,
                        const double                           time,
                        const double                           dt)
    {
      rigid_motion.locate(particle_handler, time, dt);
    }

    /** For each field: whether it belongs to a rigid grain. */
    const std::vector<bool> &
    get_field_is_rigid() const
    {
      return field_is_rigid;
    }

    /**
     * For each field: whether it holds one deformable disk or sphere of an
     * elastic material (no history variable), which keeps its shape to a
     * small strain, so that its surface is its shape placed at its centre of
     * mass (GapEstimator).
     */
    const std::vector<bool> &
    get_field_keeps_shape() const
    {
      return field_keeps_shape;
    }

    /**
     * Whether the grains have more than one velocity field (contact, or a
     * rigid grain): only then are there nodes with several fields, where
     * contact needs normals.
     */
    bool
    has_several_fields() const
    {
      return several_fields;
    }

    /**
     * Call @p action(p, particle) for every locally owned particle in the
     * order of the cache, p counting from 0.
     */
    template <typename ParticleHandlerType, typename Action>
    void
    for_each_particle(ParticleHandlerType &particle_handler,
                      Action             &&action) const
    {
      std::size_t p = 0;
      cache.for_each_particle(particle_handler,
                              [&](const auto &, auto &particle) {
                                action(p++, particle);
                              });
    }

    /**
     * Particle to grid: momenta sum_p m_p v_p S_ip and, if given, masses
     * sum_p m_p S_ip and (with them, if given) mass gradients
     * sum_p m_p grad S_ip and volumes per slot, completed on the owners.
     * The volumes have 1 + dim components per slot: the volume
     * sum_p V_p S_ip and its first moment sum_p V_p (S_ip x_p +
     * l^2 / 3 grad S_ip) (l the half-width of a point's box: the moment of
     * the box under the hat). With the volumes, if given, @p shape_sums
     * gets n_shape_sums entries per field: for a field that keeps its shape
     * (get_field_keeps_shape()) sums over its owned points (not over the
     * processes), zero for the others: the mass sum_p m_p, the
     * mass-weighted Green strain sum_p m_p |F_p^T F_p - I| / 2, the first
     * moment sum_p m_p x_p (dim entries), the momentum sum_p m_p v_p (dim),
     * the angular momentum about the origin sum_p m_p x_p x v_p (1 in 2D, 3
     * in 3D) and the second moment sum_p m_p x_p (x) x_p (dim * dim, row
     * by row).
     */
    void
    particles_to_grid(const Particles::ParticleHandler<dim> &particle_handler,
                      VectorType                            *masses,
                      VectorType                            &momenta,
                      VectorType                            *mass_gradients,
                      VectorType                            *volumes = nullptr,
                      std::vector<double> *shape_sums = nullptr) const;

    /** Entries per field of the shape sums of particles_to_grid(). */
    static constexpr unsigned int n_shape_sums =
      2 + 2 * dim + (dim == 2 ? 1 : 3) + dim * dim;

    /** v = p / m on owned slots with mass, zero elsewhere. */
    void
    velocities_from_momenta(const VectorType &masses,
                            const VectorType &momenta,
                            VectorType       &velocities) const;

    /**
     * Internal force -V_p sigma_p . grad S_ip and gravity m_p g S_ip of
     * the deformable particles per slot (explicit scheme).
     */
    void
    compute_forces(const Particles::ParticleHandler<dim> &particle_handler,
                   const Tensor<1, dim>                  &gravity,
                   VectorType                            &forces) const;

    /**
     * The velocity gradient sum_i v_i (x) grad S_ip of particle @p p (cache
     * order) from the grid velocities @p velocities (dim per local slot,
     * ghosts included).
     */
    Tensor<2, dim>
    velocity_gradient(const std::size_t p, const double *velocities) const
    {
      const unsigned int   *slots     = cache.slots.data();
      const Tensor<1, dim> *gradients = cache.shape_gradients.data();
      Tensor<2, dim>        gradient;
      cache.for_each_entry(p, [&](const unsigned int e) {
        for (unsigned int i = 0; i < dim; ++i)
          {
            const double velocity = velocities[slots[e] * dim + i];
            for (unsigned int j = 0; j < dim; ++j)
              gradient[i][j] += velocity * gradients[e][j];
          }
      });
      return gradient;
    }

    /**
     * Subtract the divergence sum_j @p stress_ij grad_j S_ip of particle
     * @p p from @p forces (dim per local slot): the internal force of a
     * stress already multiplied by the particle volume.
     */
    void
    subtract_divergence(const std::size_t p,
                        const double (&stress)[dim][dim],
                        double *forces) const
    {
      const unsigned int   *slots     = cache.slots.data();
      const Tensor<1, dim> *gradients = cache.shape_gradients.data();
      cache.for_each_entry(p, [&](const unsigned int e) {
        for (unsigned int i = 0; i < dim; ++i)
          {
            double divergence = 0.;
            for (unsigned int j = 0; j < dim; ++j)
              divergence += stress[i][j] * gradients[e][j];
            forces[slots[e] * dim + i] -= divergence;
          }
      });
    }

    /**
     * Constitutive update of every deformable particle with the strain
     * increment dt grad v from @p velocities: new stress and history,
     * F <- (I + dt grad v) F and V = det(F) V_0. Adds the plastic work
     * and the hypoelastic correction to @p ledger and, if given, the new
     * elastic energy to @p strain_energy.
     */
    void
    update_particle_states(Particles::ParticleHandler<dim> &particle_handler,
                           const VectorType                &velocities,
                           const double                     dt,
                           LedgerIncrements                &ledger,
                           double *strain_energy = nullptr) const;

    /**
     * The local elastic energy sum V W(sigma) that update_particle_states()
     * would give the deformable particles, and its plastic work added to
     * @p plastic_work, without changing the particles.
     */
    double
    trial_strain_energy(Particles::ParticleHandler<dim> &particle_handler,
                        const VectorType                &velocities,
                        const double                     dt,
                        double                          &plastic_work) const;

    /**
     * update_particle_states() and compute_forces() in one pass over the
     * particles: the forces of the new stresses and volumes (the
     * update-stress-first order of the explicit scheme).
     */
    void
    update_particle_states_and_forces(
      Particles::ParticleHandler<dim> &particle_handler,
      const VectorType                &velocities,
      const double                     dt,
      const Tensor<1, dim>            &gravity,
      VectorType                      &forces,
      LedgerIncrements                &ledger) const;

    /**
     * Grid to particle: FLIP/PIC velocity update from @p new_velocities
     * (the increment measured from @p reference_velocities; `Particle
     * velocity update`) and position update x += dt sum_i S_ip v_i with
     * v = @p position_velocities. Rigid grains follow their prescribed
     * velocity. Each point is checked (ParticleUpdateCheck). Records
     * particles that left through open faces (removed by finish_step()) and
     * whether the handler needs sorting, and the energy
     * the velocity update adds beyond the change of the grid kinetic
     * energy (LedgerIncrements::transfer_energy_change), the grid kinetic
     * energy being 1/2 v.M v with the mass matrix @p mass_matrix if given,
     * with the lumped @p masses otherwise. Throws InputError on all ranks
     * if a particle leaves through a closed face.
     */
    void
    grid_to_particles(Particles::ParticleHandler<dim> &particle_handler,
                      const VectorType                &masses,
                      const VectorType                &new_velocities,
                      const VectorType                &reference_velocities,
                      const VectorType                &position_velocities,
                      const double                     time,
                      const double                     dt,
                      StepStatistics                  &statistics,
                      const MassMatrix<dim>           *mass_matrix = nullptr);

    /**
     * Remove the particles that left, reduce @p statistics over the ranks
     * and sort the particles if some changed cells. Collective.
     */
    void
    finish_step(Particles::ParticleHandler<dim> &particle_handler,
                StepStatistics                  &statistics);

  private:
    /**
     * The half-width l of a particle's box: its share of the regular
     * arrangement of the points, half the point spacing on each side.
     */
    Tensor<1, dim>
    point_half_width() const
    {
      Tensor<1, dim> half_width;
      for (unsigned int d = 0; d < dim; ++d)
        half_width[d] = 0.5 * grid.cell_size()[d] /
                        parameters.material_points.particles_per_cell;
      return half_width;
    }

    /**
     * Add the force of particle @p p (cache order) with @p mass, @p volume
     * and @p stress under @p gravity to @p forces (dim per local slot):
     * f_s += -V sigma . grad S_sp + m S_sp g (Cummins & Brackbill eq. 7).
     */
    void
    add_force(const std::size_t            p,
              const double                 mass,
              const double                 volume,
              const SymmetricTensor<2, 3> &stress,
              const Tensor<1, dim>        &gravity,
              double                      *forces) const
    {
      cache.for_each_entry(p, [&](const unsigned int e) {
        const unsigned int    slot     = cache.slots[e];
        const double          shape    = cache.shape_values[e];
        const Tensor<1, dim> &gradient = cache.shape_gradients[e];
        for (unsigned int i = 0; i < dim; ++i)
          {
            double divergence = 0.;
            for (unsigned int j = 0; j < dim; ++j)
              divergence += stress[i][j] * gradient[j];
            forces[slot * dim + i] +=
              -volume * divergence + mass * shape * gravity[i];
          }
      });
    }

    /**
     * The loop of update_particle_states(), adding the forces to
     * @p forces (dim per local slot) if it is given; with @p store false
     * the particles keep their state (trial_strain_energy()) and the
     * hypoelastic correction is not computed.
     */
    void
    update_states(Particles::ParticleHandler<dim> &particle_handler,
                  const VectorType                &velocities,
                  const double                     dt,
                  LedgerIncrements                &ledger,
                  double                          *strain_energy,
                  const Tensor<1, dim>            &gravity,
                  VectorType                      *forces,
                  const bool                       store = true) const;

    /**
     * The FLIP/PIC update of the deformable particle @p p (cache order)
     * with @p properties at @p old_position: v_p = flip (v_p + sum_i S_ip
     * (v_i^new - v_i^ref)) + (1 - flip) sum_i S_ip v_i^new and
     * x_p += dt sum_i S_ip v_i^x, from the grid values @p new_values,
     * @p reference_values and @p position_values (dim per local slot).
     * Adds to @p kinetic_change the change of 1/2 m_p |v_p|^2 and to
     * @p increment_energy 1/2 m_p |sum_i S_ip (v_i^new - v_i^ref)|^2.
     */
    void
    update_deformable(const std::size_t        p,
                      const ArrayView<double> &properties,
                      const Point<dim>        &old_position,
                      const double            *new_values,
                      const double            *reference_values,
                      const double            *position_values,
                      const double             dt,
                      Point<dim>              &new_position,
                      Tensor<1, dim>          &new_velocity,
                      double                  &kinetic_change,
                      double                  &increment_energy) const;

    /**
     * Add the kinetic and elastic energy, the momentum and the first moment
     * of the deformable particle with @p properties of grain @p grain at
     * @p position with @p velocity to @p sums.
     */
    void
    add_particle_sums(const ArrayView<const double> &properties,
                      const unsigned int             grain,
                      const Tensor<1, dim>          &velocity,
                      const Point<dim>              &position,
                      ParticleSums                  &sums) const;

    /**
     * Move @p particle from @p old_position to @p new_position, keeping its
     * cell if it is still inside; otherwise mark the handler for sorting in
     * @p statistics.
     */
    void
    move_particle(
      typename Particles::ParticleHandler<dim>::particle_iterator &particle,
      const Point<dim>                                            &old_position,
      const Point<dim>                                            &new_position,
      StepStatistics &statistics) const;

    /**
     * Book in @p ledger the energy the velocity update adds beyond the
     * change of the grid kinetic energy of the deformable fields,
     * @p kinetic_change - 1/2 sum_s m_s (|v_s^new|^2 - |v_s^ref|^2) (with
     * @p mass_matrix if given and not lumped: 1/2 v.M v), and with
     * TransferOptions::book_leapfrog_energy_change the leapfrog's
     * @p increment_energy - 1/2 sum_s m_s |v_s^new - v_s^ref|^2; this
     * rank's slots.
     */
    void
    book_energy_changes(const VectorType      &masses,
                        const VectorType      &new_velocities,
                        const VectorType      &reference_velocities,
                        const MassMatrix<dim> *mass_matrix,
                        const double           kinetic_change,
                        const double           increment_energy,
                        LedgerIncrements      &ledger) const;

    const Parameters<dim>                                      &parameters;
    const BackgroundGrid<dim>                                  &grid;
    const std::vector<GrainInfo<dim>>                          &grains;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;
    const TransferOptions                                       options;
    RigidGrainMotion<dim>                                       rigid_motion;
    const ParticleUpdateCheck<dim>                              update_check;

    std::vector<unsigned int> field_of_grain;
    std::vector<bool>         field_is_rigid;
    std::vector<bool>         field_keeps_shape;
    bool                      several_fields = false;
    TransferCache<dim>        cache;
    GrainFieldLayout<dim>     layout;

    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      particles_to_remove;
  };
} // namespace grainmpm

#endif
