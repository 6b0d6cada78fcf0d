// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_theta_residual_h
#define grainmpm_time_integration_theta_residual_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/solvers/newton_krylov.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  using namespace dealii;

  /**
   * The residual of the implicit theta scheme (seed eq. 16,
   * reference/physics.md sections 4.2-4.4), divided by the slot mass so
   * that it has velocity units. The unknown V holds v^{n+1} for every slot
   * (dim numbers per slot, the layout of GrainFieldLayout):
   *
   *   R_s(V) = V_s - v^n_s - dt (f^int_s(sigma^theta, V^theta) / m_s + g),
   *
   * where the internal force is -sum_p V_p^theta sigma_p^theta . grad S_ip
   * over the particles of the slot's grain, with
   * sigma^theta = (1 - theta) sigma^n + theta Phi(sigma^n, dt grad v^theta),
   * V^theta = (1 - theta) V^n + theta det(I + dt grad v^theta) V^n, and
   * v^theta = Pi((1 - theta) v^n + theta V), Pi being the contact
   * projection and the wall conditions with the contact status frozen by
   * freeze_status(). The projected end velocity is
   * Pi_theta(V) = (v^theta - (1 - theta) v^n) / theta. Slots of rigid
   * grains have R = V - (prescribed velocity at t + dt); slots with less
   * than 1e-6 of the largest particle mass (m_min, reference/physics.md
   * section 8.5) R = V - v^n - dt g.
   *
   * The constraints act on v^theta, the velocity that moves the particles
   * and strains them, not on v^{n+1}: then no grain moves into another or
   * into a wall within the step, and a frictionless reaction does no work,
   * because it is normal to v^theta - v_ref where it acts. With theta = 1/2
   * the grid step then conserves energy through contact and wall impacts
   * (doc/validation.md). Constraining v^{n+1} instead (reference/physics.md
   * 4.4) lets the reaction do work wherever a slot separating at t^n is
   * pushed back, which gained 75 % of E0 in five wall impacts of
   * prm/single_grain_rebound_implicit.prm. Status decisions are taken on
   * the trial theta velocity accordingly.
   *
   * Everything the residual reads at t^n is copied once per step into flat
   * arrays in the order of the TransferCache (stress, volume, history,
   * material of each particle), so that a residual evaluation never goes
   * through the particle handler and never writes particle state: it is a
   * `const` function of V, and two calls with the same V and status give
   * bit-identical results (the loops are serial and in a fixed order).
   *
   * The contact status of a slot at a contact node is free, sliding (the
   * normal part of v - v_ref is removed and, with Coulomb friction, the
   * tangential part reduced by mu times the normal part along a frozen
   * slip direction) or sticking (v = v_ref). v_ref is the velocity of a
   * rigid partner or the centre-of-mass velocity of the node, computed from
   * V; with three or more deformable fields a common shift restores the
   * node's momentum after the projection. Walls are frozen likewise per
   * (slot, face). Given the status, Pi is linear in V, so the
   * finite-difference Jacobian never straddles a switch.
   *
   * The simplified Jacobian of the preconditioner (eq. 20) holds v_ref at
   * contact nodes fixed at its value at the freezing point and skips the
   * momentum shift; then slots couple only to slots of the same field in
   * the 3^dim node neighbourhood, and its diagonal is probed with
   * 2 3^dim (2D: 18, 3D: 81) coloured residual evaluations.
   */
  template <int dim>
  class ThetaResidual : public NonlinearProblem
  {
  public:
    using VectorType = NonlinearProblem::VectorType;

    ThetaResidual(
      const ContactParameters   &contact,
      const BackgroundGrid<dim> &grid,
      const std::vector<bool>   &field_is_rigid,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    /**
     * Set up the step from @p time to @p time + @p dt: copy the particle
     * state of @p particle_handler (visited in the order of @p cache), and
     * keep references to the slot @p masses, contact @p normals, the
     * velocities @p old_velocities (v^n after contact and walls) and the
     * prescribed velocities @p rigid_velocities at t + dt of rigid slots.
     * All referenced objects must live until the step is done.
     */
    void
    reinit(const TransferCache<dim>              &cache,
           const GrainFieldLayout<dim>           &layout,
           const Particles::ParticleHandler<dim> &particle_handler,
           const std::vector<GrainInfo<dim>>     &grains,
           const VectorType                      &masses,
           const VectorType                      &normals,
           const VectorType                      &old_velocities,
           const VectorType                      &rigid_velocities,
           const Tensor<1, dim>                  &gravity,
           const double                           theta,
           const double                           dt);

    /**
     * Freeze the contact and wall status at @p velocities (a trial
     * v^{n+1}). Says whether a discrete state (free, sliding, sticking) or
     * only a slip direction differs from the status frozen before.
     */
    Change
    freeze_status(const VectorType &velocities);

    /** evaluate(@p x, @p r). */
    void
    residual(const VectorType &x, VectorType &r) override
    {
      evaluate(x, r);
    }

    /** freeze_status(@p x). */
    Change
    update_linearization(const VectorType &x) override
    {
      return freeze_status(x);
    }

    /**
     * The simplified residual at @p x and probe_diagonal() from it.
     */
    void
    jacobian_diagonal(const VectorType   &x,
                      const StepFunction &step,
                      VectorType         &diagonal) override;

    unsigned long
    n_residual_evaluations() const override
    {
      return evaluation_count;
    }

    /**
     * R(@p velocities) into @p residual (which must have the layout of
     * the unknowns). With @p simplified, v_ref at contact nodes is the
     * frozen one and the momentum shift is skipped (the preconditioner's
     * Jacobian).
     */
    void
    evaluate(const VectorType &velocities,
             VectorType       &residual,
             const bool        simplified = false,
             const bool        raw        = false) const;

    /**
     * The contact- and wall-projected end velocities Pi_theta(@p
     * velocities) with the frozen status: the projection acts on the theta
     * velocity. Returns the number of nodes where contact is active.
     */
    unsigned int
    project(const VectorType           &velocities,
            VectorType                 &projected,
            std::vector<unsigned char> *node_in_contact = nullptr) const;

    /**
     * The diagonal of the simplified Jacobian dR/dV at @p velocities by
     * coloured probing; @p residual must be the simplified residual at
     * @p velocities. @p step(x, z) gives the differencing step for the
     * perturbation z. Rows of rigid and massless slots are 1.
     */
    void
    probe_diagonal(const VectorType   &velocities,
                   const VectorType   &residual,
                   VectorType         &diagonal,
                   const StepFunction &step) const;

    /** Number of colours of probe_diagonal(). */
    static constexpr unsigned int n_colours = dim * (dim == 2 ? 9 : 27);

    /** Colour of unknown @p dof (slot * dim + component). */
    unsigned int
    colour(const unsigned int dof) const;

    /**
     * The new stress, history, increment dt grad v^theta and volume
     * factor det(I + dt grad v^theta) of particle @p p (cache order) for
     * the time-centred grid velocity @p theta_velocities.
     */
    void
    particle_update(const std::size_t      p,
                    const VectorType      &theta_velocities,
                    SymmetricTensor<2, 3> &new_stress,
                    double                &new_plastic_strain,
                    Tensor<2, dim>        &increment) const;

    /** Whether particle @p p (cache order) belongs to a deformable grain. */
    bool
    is_deformable(const std::size_t p) const
    {
      return particle_models[p] != nullptr;
    }

    /** sum_p V_p W(sigma_p) of the deformable particles at t^n. */
    double
    old_strain_energy() const;

    /** v^theta = (1 - theta) v^n + theta @p projected into @p theta_v. */
    void
    theta_velocities(const VectorType &projected, VectorType &theta_v) const;

    /** Whether slot @p slot is an unknown of the elastic system. */
    bool
    is_active(const unsigned int slot) const
    {
      return slot_active[slot];
    }

  private:
    /** Contact status of a slot. */
    enum State : unsigned char
    {
      free     = 0,
      sliding  = 1,
      sticking = 2
    };

    /**
     * Where the contact projection takes the reference velocity v_ref of a
     * node: from the vector it acts on (the rigid slot or the centre of
     * mass), the value frozen with the status (simplified Jacobian), or
     * zero (the linear part of the simplified projection).
     */
    enum class ReferenceMode
    {
      from_vector,
      frozen,
      zero
    };

    /**
     * Apply the frozen contact projection to @p v in place; flags and
     * counts the nodes where it is active.
     */
    unsigned int
    apply_frozen_contact(VectorType                 &v,
                         const ReferenceMode         mode,
                         std::vector<unsigned char> *node_flags) const;

    /**
     * Frozen contact, then frozen walls, on the end velocities @p v in
     * place, acting on the theta velocity (1 - theta) v^n + theta v; with
     * ReferenceMode::zero the linear part of that map, which acts on
     * differences of velocities directly.
     */
    unsigned int
    apply_projection(VectorType                 &v,
                     const ReferenceMode         mode,
                     std::vector<unsigned char> *node_in_contact) const;

    /**
     * The contact state of a velocity @p relative to the partner (or wall)
     * with normal @p normal and friction coefficient @p mu; sets the slip
     * direction of a sliding state with friction, zero otherwise.
     */
    static unsigned char
    classify(const Tensor<1, dim> &relative,
             const Tensor<1, dim> &normal,
             const double          mu,
             Tensor<1, dim>       &slip_direction);

    /** Apply wall entry @p w with its frozen status to @p velocity. */
    void
    apply_wall_entry(const unsigned int w, Tensor<1, dim> &velocity) const;

    /** The communicator of the grid. */
    MPI_Comm
    communicator() const
    {
      return grid.get_triangulation().get_communicator();
    }

    /** Stress and history update of particle @p p for v^theta. */
    void
    compute_particle(const std::size_t      p,
                     const VectorType      &theta_v,
                     SymmetricTensor<2, 3> &new_stress,
                     double                &plastic_strain,
                     Tensor<2, dim>        &increment) const;

    const ContactParameters                                    &contact;
    const BackgroundGrid<dim>                                  &grid;
    const std::vector<bool>                                    &field_is_rigid;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;

    const TransferCache<dim>    *cache            = nullptr;
    const GrainFieldLayout<dim> *layout           = nullptr;
    const VectorType            *masses           = nullptr;
    const VectorType            *normals          = nullptr;
    const VectorType            *old_velocities   = nullptr;
    const VectorType            *rigid_velocities = nullptr;
    Tensor<1, dim>               gravity;
    double                       theta = 0.5;
    double                       dt    = 0.;

    /** The structure-of-arrays particle mirror (cache order). */
    std::vector<const ConstitutiveModel<dim> *> particle_models;
    std::vector<SymmetricTensor<2, 3>>          particle_stresses;
    std::vector<double>                         particle_volumes;
    std::vector<double>                         particle_plastic_strains;

    std::vector<bool> slot_active;
    std::vector<bool> slot_rigid;

    /** Whether any slot or wall entry is not free. */
    bool any_constraint_active = false;

    /** Frozen contact status per slot, slip directions, frozen v_ref. */
    std::vector<unsigned char>  slot_state;
    std::vector<Tensor<1, dim>> slip_directions;
    std::vector<Tensor<1, dim>> frozen_references;

    /** Wall entries (slot, face) and their frozen status. */
    std::vector<unsigned int>   wall_slots;
    std::vector<unsigned char>  wall_faces;
    std::vector<unsigned char>  wall_state;
    std::vector<Tensor<1, dim>> wall_slip_directions;

    /** Work vectors of evaluate(). */
    mutable VectorType    work_projected;
    mutable VectorType    work_theta;
    mutable VectorType    work_forces;
    mutable unsigned long evaluation_count = 0;
  };



} // namespace grainmpm

#endif
