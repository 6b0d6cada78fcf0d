// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_theta_residual_h
#define grainmpm_time_integration_theta_residual_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/contact/held_contact_status.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/solvers/newton_krylov.h>
#include <grainmpm/time_integration/implicit/elastic_preconditioner.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  /**
   * The residual of the implicit theta scheme (Cummins & Brackbill 2001,
   * eq. 16), divided by the lumped slot mass m_s so
   * that it has velocity units. The unknown V holds v^{n+1} for every slot
   * (dim numbers per slot, the layout of GrainFieldLayout):
   *
   *   R_s(V) = (M (V - v^n))_s / m_s - dt (f^int_s(sigma^theta, V^theta) / m_s
   *            + g),
   *
   * M being the grid mass matrix (MassMatrix: the lumped mass, for which
   * the first term is V_s - v^n_s, or its blend with the consistent mass),
   * where the internal force is -sum_p V_p^theta sigma_p^theta . grad S_ip
   * over the particles of the slot's grain, with
   * sigma^theta = (1 - theta) sigma^n + theta Phi(sigma^n, dt grad v^theta),
   * V^theta = (1 - theta) V^n + theta det(I + dt grad v^theta) V^n, and
   * v^theta = Pi((1 - theta) v^n + theta V), Pi being the contact
   * projection and the wall conditions with the contact status frozen by
   * freeze_status(). The projected end velocity is
   * Pi_theta(V) = (v^theta - (1 - theta) v^n) / theta. Slots of rigid
   * grains have R = V - (prescribed velocity at t + dt); slots with less
   * than 1e-6 of the largest particle mass carry no force:
   * R = (M (V - v^n))_s / m_s - dt g.
   *
   * The constraints act on v^theta, the velocity that moves the particles
   * and strains them, not on v^{n+1}: then no grain moves into another or
   * into a wall within the step, and a frictionless reaction does no work,
   * because it is normal to v^theta - v_ref where it acts. With theta = 1/2
   * the grid step then conserves energy through contact and wall impacts
   * (doc/validation.md). Constraining v^{n+1} instead lets the reaction do work
   * wherever a slot separating at t^n is pushed back, which gained 75 % of E0
   * in five wall impacts of prm/single_grain_rebound_implicit.prm. Status
   * decisions are taken on the trial theta velocity accordingly.
   *
   * Everything the residual reads at t^n is copied once per step into flat
   * arrays in the order of the TransferCache (stress, volume, history,
   * material of each particle), so that a residual evaluation never goes
   * through the particle handler and never writes particle state: it is a
   * `const` function of V, and two calls with the same V and status give
   * bit-identical results (the loops are serial and in a fixed order).
   *
   * Pi is the contact law of GrainContact with its status frozen
   * (ContactStatus::freeze, ContactStatus::apply): per slot at a
   * contact node free, sliding or sticking, with v_ref the velocity of a
   * rigid partner or the centre-of-mass velocity of the node computed from
   * V, and at nodes of three or more deformable fields the projection
   * alternated with the momentum-restoring shift; walls are frozen
   * likewise per (slot, face). Given the status, Pi is linear in V, so the
   * finite-difference Jacobian never straddles a switch.
   *
   * The simplified Jacobian of the preconditioner (eq. 20) holds v_ref at
   * contact nodes fixed at its value at the freezing point and skips the
   * momentum shift; then a slot couples only to slots of the same field
   * at nodes that share a particle with its node: at most one node away
   * per axis with linear shape functions, two with GIMP (a point touches
   * up to 3 nodes per axis). Nodes with the same index modulo 3 per axis
   * never share a particle, so the diagonal is probed exactly for every
   * kernel with 2 3^dim (2D: 18, 3D: 81) coloured residual evaluations.
   */
  template <int dim>
  class ThetaResidual : public NonlinearProblem
  {
  public:
    using VectorType = NonlinearProblem::VectorType;

    /**
     * The residual with the contact law @p contact on @p grid.
     */
    ThetaResidual(
      const GrainContact<dim>                                    &contact,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);

    /**
     * Set up the step from @p time to @p time + @p dt: copy the particle
     * state of @p particle_handler (visited in the order of the transfer
     * cache of @p transfer), and keep references to @p transfer, the slot
     * @p masses, contact @p normals, the velocities @p old_velocities (v^n
     * after contact and walls) and the prescribed velocities
     * @p rigid_velocities at t + dt of rigid slots, and the grid
     * @p mass_matrix (set up with @p masses). All referenced objects
     * must live until the step is done.
     */
    void
    reinit(const Transfer<dim>                   &transfer,
           const Particles::ParticleHandler<dim> &particle_handler,
           const MassMatrix<dim>                 &mass_matrix,
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
     * only a slip direction differs from the status frozen before; a
     * change of the discrete state of at most max_minor_status_change
     * slots and wall entries (over all ranks) is a minor one. With
     * @p monotone no free slot or wall entry is caught
     * (ContactStatus::freeze()).
     */
    Change
    freeze_status(const VectorType &velocities, const bool monotone = false);

    /**
     * The largest number of slots and wall entries whose discrete state
     * may change for the change to be minor, so that the assembled
     * preconditioner is kept through it: a few slots change A little, and
     * GMRES makes up the difference.
     */
    static constexpr unsigned int max_minor_status_change = 4;

    /**
     * The hysteresis band of the status decisions after the first in a
     * step (a velocity; GrainContact::freeze()).
     */
    void
    set_status_band(const double band)
    {
      status_band = band;
    }

    /** How the assembled preconditioner inverts its matrix. */
    void
    set_preconditioner_inverse(
      const typename ElasticPreconditioner<dim>::Inverse inverse)
    {
      preconditioner.set_inverse(inverse);
    }

    /** The contact status frozen at present. */
    const ContactStatus<dim> &
    get_contact_status() const
    {
      return status;
    }

    /**
     * Start the status of this step from @p held (the status an earlier
     * step converged to; HeldContactStatus::apply()) instead of deciding
     * it afresh at the first iterate. Call after reinit().
     */
    void
    start_status_from(const HeldContactStatus<dim> &held)
    {
      held.apply(status, *layout, contact.get_grid());
      ++status_generation;
    }

    /** evaluate(@p x, @p r). */
    void
    residual(const VectorType &x, VectorType &r) override
    {
      evaluate(x, r);
    }

    /** freeze_status(@p x, @p monotone). */
    Change
    update_linearization(const VectorType &x, const bool monotone) override
    {
      return freeze_status(x, monotone);
    }

    /**
     * Set up the elastic preconditioner (ElasticPreconditioner::setup())
     * for the status frozen at present: it probes the linear part of the
     * projection (ContactStatus::apply_symmetric_linear_part()) slot by
     * slot. @p x is not used: the elastic stiffness is that of
     * the particles at t^n.
     */
    void
    setup_preconditioner(const VectorType &x) override;

    /** ElasticPreconditioner::vmult(). */
    void
    apply_preconditioner(VectorType &dst, const VectorType &src) override
    {
      preconditioner.vmult(dst, src);
    }

    /** The assembled preconditioner (for tests). */
    const ElasticPreconditioner<dim> &
    get_preconditioner() const
    {
      return preconditioner;
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
     * "a material point inverts (...)" if the last evaluation of any rank
     * met a particle with det(I + dt grad v^theta) <= 0, which makes the
     * residual NaN; empty otherwise. Collective.
     */
    std::string
    why_not_finite() const override;

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
     * evaluate(@p velocities, @p raw, false, true), the raw residual with
     * the present status, taken from the last full evaluation if that was
     * at these velocities with this status (on every rank): the iterate
     * the line search accepted, at the status decision after it and at
     * the end of a converged solve.
     */
    void
    raw_residual_at(const VectorType &velocities, VectorType &raw) const;

    /**
     * The contact- and wall-projected end velocities Pi_theta(@p
     * velocities) with the frozen status: the projection acts on the theta
     * velocity. Returns the number of nodes where contact is active. With
     * @p impulses, adds the impulses the projection gives the end
     * velocities.
     */
    unsigned int
    project(const VectorType           &velocities,
            VectorType                 &projected,
            std::vector<unsigned char> *node_in_contact = nullptr,
            ConstraintImpulses<dim>    *impulses        = nullptr) const;

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
    /**
     * Frozen contact, then frozen walls, on the end velocities @p v in
     * place, acting on the theta velocity (1 - theta) v^n + theta v: with
     * v_ref from the velocities (ContactStatus::apply()) or, if
     * @p simplified, frozen (ContactStatus::apply_simplified()). Records
     * @p impulses if given.
     */
    unsigned int
    apply_projection(VectorType                 &v,
                     const bool                  simplified,
                     std::vector<unsigned char> *node_in_contact,
                     ConstraintImpulses<dim>    *impulses = nullptr) const;

    /**
     * The internal forces f_s (eqs. 12-13) at the theta velocities in
     * work_theta (ghosts updated) into work_forces. Returns whether a
     * particle is inverted (det(I + dt grad v^theta) <= 0).
     */
    bool
    assemble_internal_forces() const;

    /**
     * The raw residual R_raw = M_L^-1 M (V - v^n) - dt (f / m + g) of
     * @p velocities into @p residual, from work_forces (and work_inertia
     * with the blended mass); rigid slots R = V - prescribed velocity.
     */
    void
    raw_residual(const VectorType &velocities, VectorType &residual) const;

    /**
     * The constrained form P R_raw + (V - P V) of the raw residual in
     * @p residual in place, P V being work_projected; with @p simplified
     * the linear part of the projection.
     */
    void
    constrain_residual(const VectorType &velocities,
                       VectorType       &residual,
                       const bool        simplified) const;

    /** The communicator of the grid. */
    MPI_Comm
    communicator() const
    {
      return grid.get_triangulation().get_communicator();
    }

    const GrainContact<dim>                                    &contact;
    const BackgroundGrid<dim>                                  &grid;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;

    const Transfer<dim>         *transfer         = nullptr;
    const GrainFieldLayout<dim> *layout           = nullptr;
    const MassMatrix<dim>       *mass_matrix      = nullptr;
    const VectorType            *masses           = nullptr;
    const VectorType            *normals          = nullptr;
    const VectorType            *old_velocities   = nullptr;
    const VectorType            *rigid_velocities = nullptr;
    Tensor<1, dim>               gravity;
    double                       theta = 0.5;
    double                       dt    = 0.;
    /** Slots with no more mass than this are not unknowns. */
    double mass_threshold = 0.;

    /** The structure-of-arrays particle mirror (cache order). */
    std::vector<const ConstitutiveModel<dim> *> particle_models;
    /** The stress the model updates: J sigma (Kirchhoff, J = V / V0) or
     * the Cauchy stress sigma (ConstitutiveModel::rate_stress_factor()). */
    std::vector<SymmetricTensor<2, 3>> particle_rate_stresses;
    std::vector<double>                particle_volumes;
    /** Volumes at t = 0 (the energy of the Kirchhoff stress is per V0). */
    std::vector<double> particle_initial_volumes;
    std::vector<double> particle_plastic_strains;

    std::vector<bool> slot_active;
    std::vector<bool> slot_rigid;

    /** The frozen contact and wall status. */
    ContactStatus<dim> status;
    /**
     * Counts the changes of #status (and of the step, reinit()); a
     * decision that leaves the status as it was does not count.
     */
    unsigned long status_generation = 1;

    /** The hysteresis band of the status decisions. */
    double status_band = 0.;

    /** The assembled preconditioner, set up by setup_preconditioner(). */
    ElasticPreconditioner<dim> preconditioner;
    /** Whether the slots changed since the preconditioner was assembled. */
    bool preconditioner_pattern_stale = true;

    /** Work vectors of evaluate(). */
    mutable VectorType work_projected;
    mutable VectorType work_theta;
    mutable VectorType work_forces;
    /** V - v^n and M (V - v^n) (blended mass only). */
    mutable VectorType    work_increment;
    mutable VectorType    work_inertia;
    mutable unsigned long evaluation_count = 0;
    /** Whether the last evaluation inverted a particle on this rank. */
    mutable bool last_evaluation_inverted = false;

    /**
     * The raw residual of the last full evaluation, the velocities it was
     * evaluated at and the #status_generation it was evaluated with (zero:
     * none), for raw_residual_at().
     */
    mutable VectorType    cached_raw_residual;
    mutable VectorType    cached_velocities;
    mutable unsigned long cached_generation = 0;
  };



} // namespace grainmpm

#endif
