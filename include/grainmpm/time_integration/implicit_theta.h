// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_implicit_theta_h
#define grainmpm_time_integration_implicit_theta_h

#include <grainmpm/base/config.h>
#include <grainmpm/solvers/newton_krylov.h>
#include <grainmpm/time_integration/step_error_estimator.h>
#include <grainmpm/time_integration/theta_residual.h>
#include <grainmpm/time_integration/time_integrator.h>

namespace grainmpm
{
  /**
   * The fully implicit theta step of Cummins & Brackbill (2001), eqs.
   * (11)-(20):
   *
   * 1. P2G of mass, momentum and mass gradients at t^n; v^n from
   *    M v^n = p with the grid mass matrix M (`Time stepping/Mass
   *    matrix`: lumped, or blended with the consistent mass); contact and
   *    walls on v^n (the reference v^n of the step); normals frozen.
   * 2. Solve R(v^{n+1}) = 0 (ThetaResidual) by Jacobian-free Newton-Krylov
   *    (NewtonKrylovSolver) from v^n or an explicit predictor.
   * 3. Momentum-exact final velocity v* = V - R(V) (with the lumped mass
   *    v^n + dt (f / m + g), the forces of the converged iterate), then the
   *    contact
   *    projection and walls with the converged status: the grid velocity
   *    v^{n+1}. Total momentum then changes exactly by the external
   *    impulse, whatever the Newton tolerance.
   * 4. Stress, history, deformation gradient and volume from
   *    v^theta = (1 - theta) v^n + theta v^{n+1}; FLIP (or PIC, blend)
   *    particle velocities from v^{n+1} - v^n_P2G; positions moved with
   *    v^theta (second order at theta = 1/2).
   *
   * If the solve fails, advance() returns `solver.converged == false` with the
   * reason and leaves the particles untouched, so that the caller can
   * retry with a smaller step.
   */
  template <int dim>
  class ImplicitTheta : public TimeIntegrator<dim>
  {
  public:
    using VectorType = typename TimeIntegrator<dim>::VectorType;

    /**
     * The lines of `Nonlinear solver/Verbose` go to the screen of the
     * first rank unless @p quiet (`grainmpm --quiet`).
     */
    ImplicitTheta(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
      const bool quiet = false);

    StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt) override;

    /**
     * Set up the residual of the step from @p time by @p dt without
     * solving: P2G, v^n with contact, the residual, with the status frozen
     * at v^n if @p freeze. Used by advance() and by the unit tests and
     * benchmarks.
     */
    ThetaResidual<dim> &
    prepare(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt,
            const bool                       freeze = true);

    /** v^n of the last prepared step (after contact and walls). */
    const VectorType &
    get_old_velocities() const
    {
      return velocities_old;
    }

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

    /** The contact status where the next step starts. */
    HeldContactStatus<dim> *
    get_held_contact_status() override
    {
      return &held_status;
    }

    /** The error estimate of the steps (their accelerations). */
    StepErrorEstimator<dim> *
    get_step_error_estimator() override
    {
      return &step_error;
    }

    /** Whether the last step was quasi-static (see step_theta()). */
    bool *
    get_quasi_static_flag() override
    {
      return &last_step_quasi_static;
    }

    /** Where the contact locates the rigid grains. */
    RigidGrainMotion<dim> *
    get_rigid_grain_motion() override
    {
      return &transfer.get_rigid_motion();
    }

    /** The Newton-Krylov solver. */
    const NewtonKrylovSolver &
    get_solver() const
    {
      return solver;
    }

    /** The grid mass matrix of the last prepared step. */
    const MassMatrix<dim> &
    get_mass_matrix() const
    {
      return mass_matrix;
    }

    /**
     * Grid energy 1/2 v.M v + sum_p V_p W(sigma_p) of the deformable
     * grains at the start and at the end of the last step.
     */
    std::pair<double, double>
    get_grid_energies() const
    {
      return grid_energies;
    }

  private:
    /**
     * The centring of the next step: `Theta`, or with steps that grow
     * after a quasi-static step (grid kinetic energy at most 1 % of the
     * elastic energy at both ends) the larger of it and `Quasi-static
     * theta`.
     */
    double
    step_theta() const;

    /**
     * With steps that grow (TimeSteppingParameters::largest_time_step()):
     * why the converged step, if
     * longer than nominal_step_at_rest, is rejected for the energy its
     * grid step creates or its normal contact reactions take out (more
     * than `Energy error per step` of the grid energy), or an empty
     * string. @p kinetic_old and @p kinetic_new are the local grid kinetic
     * energies, @p constraint_work the local friction less boundary work
     * of the step; the new elastic energy comes from a trial constitutive
     * update with the theta velocities, the energy of the normal reactions
     * from GrainContact::normal_dissipation() with the projection of the
     * end velocity.
     */
    std::string
    energy_error(Particles::ParticleHandler<dim> &particle_handler,
                 const double                     kinetic_old,
                 const double                     kinetic_new,
                 const double                     constraint_work,
                 const double                     dt) const;

    const Parameters<dim> &parameters;
    Transfer<dim>          transfer;
    GrainContact<dim>      contact;
    /**
     * Steps longer than this have grown beyond the nominal step (that of
     * the material at rest), and their energy is checked.
     */
    const double nominal_step_at_rest;
    /**
     * Whether the steps may grow beyond nominal_step_at_rest: then the
     * error of each step is estimated and a grown step's energy checked.
     */
    const bool steps_grow;
    /**
     * The step of CFL number 1, h / c (the smallest cell, the largest
     * wave speed at rest): the CFL number of a step chooses its
     * preconditioner under `Preconditioner = automatic`.
     */
    const double    unit_cfl_step;
    GridState<dim>  state;
    MassMatrix<dim> mass_matrix;

    ThetaResidual<dim> residual;
    /** The contact status of the last step, where the next one starts. */
    HeldContactStatus<dim> held_status;
    /** The error of each step from the change of its accelerations. */
    StepErrorEstimator<dim>   step_error;
    NewtonKrylovSolver        solver;
    VectorType                velocities_old;
    VectorType                rigid_velocities;
    VectorType                unknowns;
    VectorType                final_residual;
    VectorType                theta_velocities;
    std::pair<double, double> grid_energies;
    /** Whether the last accepted step was quasi-static. */
    bool last_step_quasi_static = false;
  };
} // namespace grainmpm

#endif
