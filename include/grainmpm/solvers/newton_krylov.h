// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_solvers_newton_krylov_h
#define grainmpm_solvers_newton_krylov_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>
#include <string>

namespace grainmpm
{
  /**
   * A nonlinear system R(x) = 0 as the Jacobian-free Newton-Krylov solver
   * sees it: residual evaluations, a linearisation state that is frozen
   * between Newton iterations (the contact status of the implicit MPM
   * step), and a matrix-free estimate of the diagonal of (a simplification
   * of) the Jacobian for the preconditioner.
   */
  class NonlinearProblem
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;
    /** A differencing step eps for perturbing x along z. */
    using StepFunction =
      std::function<double(const VectorType &x, const VectorType &z)>;

    /** What update_linearization() changed. */
    enum class Change
    {
      none,
      continuous,
      discrete
    };

    virtual ~NonlinearProblem() = default;

    /** R(@p x) with the frozen linearisation state. */
    virtual void
    residual(const VectorType &x, VectorType &r) = 0;

    /** Freeze the linearisation state at @p x. */
    virtual Change
    update_linearization(const VectorType &x) = 0;

    /**
     * Set up an assembled preconditioner of the Jacobian at @p x (with
     * the frozen linearisation state). Problems without one do not
     * override it.
     */
    virtual void
    setup_preconditioner(const VectorType & /*x*/)
    {
      AssertThrow(false,
                  ExcMessage("This problem has no assembled preconditioner: "
                             "set Linear solver/Preconditioner to probed "
                             "Jacobi or none."));
    }

    /**
     * @p dst = approximately J^-1 @p src with the preconditioner of
     * setup_preconditioner().
     */
    virtual void
    apply_preconditioner(VectorType & /*dst*/, const VectorType & /*src*/)
    {
      AssertThrow(false, ExcInternalError());
    }

    /** Diagonal of the preconditioner's Jacobian at @p x. */
    virtual void
    jacobian_diagonal(const VectorType   &x,
                      const StepFunction &step,
                      VectorType         &diagonal) = 0;

    /** Residual evaluations so far (all kinds). */
    virtual unsigned long
    n_residual_evaluations() const = 0;
  };



  /**
   * What one Newton solve did.
   */
  struct NewtonStatistics
  {
    bool          converged = false;
    std::string   failure;
    unsigned int  iterations           = 0;
    unsigned int  linear_iterations    = 0;
    unsigned int  status_changes       = 0;
    unsigned long residual_evaluations = 0;
    /** Final root-mean-square of R divided by the velocity scale U. */
    double residual_norm = 0.;
  };



  /**
   * Inexact Newton with a matrix-free Krylov solver (doc/theory.md sections
   * 10-11; Knoll & Keyes 2004; equation numbers of Cummins & Brackbill
   * 2001): J dx = -R solved by deal.II's SolverGMRES with right
   * preconditioning (eq. 17) or SolverFGMRES to the relative tolerance
   * eta_k (constant or Eisenstat-Walker choice 2), J z by the finite
   * difference (R(x + eps z) - R(x)) / eps (eq. 15), weighted Jacobi with
   * the probed diagonal (eqs. 18-20) or no preconditioner, and a
   * backtracking line search on ||R||. Stops when
   * ||R|| <= Tolerance F_scale or RMS(R) <= Absolute tolerance U, U being
   * the velocity scale.
   */
  class NewtonKrylovSolver
  {
  public:
    using VectorType = NonlinearProblem::VectorType;

    NewtonKrylovSolver(const NonlinearSolverParameters &nonlinear,
                       const LinearSolverParameters    &linear,
                       const double                     velocity_scale);

    /**
     * Solve R(@p x) = 0 from the initial guess @p x. On failure
     * `converged` is false, `failure` says why, and @p x is the last
     * iterate.
     */
    NewtonStatistics
    solve(NonlinearProblem &problem, VectorType &x) const;

    /** The velocity scale U of the tolerances and differencing steps. */
    double
    get_velocity_scale() const
    {
      return velocity_scale;
    }

    /** The differencing step for perturbing @p x along @p z. */
    double
    differencing_step(const VectorType &x, const VectorType &z) const;

    /**
     * The finite-difference Jacobian-vector product at @p x with
     * @p r = R(@p x): @p jz = (R(x + eps z) - r) / eps.
     */
    void
    jacobian_vmult(NonlinearProblem &problem,
                   const VectorType &x,
                   const VectorType &r,
                   const VectorType &z,
                   VectorType       &jz) const;

  private:
    const NonlinearSolverParameters &nonlinear;
    const LinearSolverParameters    &linear;
    const double                     velocity_scale;
  };
} // namespace grainmpm

#endif
