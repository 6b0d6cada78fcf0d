// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_solvers_newton_krylov_h
#define grainmpm_solvers_newton_krylov_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>
#include <iostream>
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

    /**
     * What update_linearization() changed: nothing, something continuous
     * (a slip direction), a discrete state that leaves an assembled
     * preconditioner good enough to keep (minor), or one that does not.
     * Newton restarts after a minor or a discrete change.
     */
    enum class Change
    {
      none,
      continuous,
      minor,
      discrete
    };

    virtual ~NonlinearProblem() = default;

    /** R(@p x) with the frozen linearisation state. */
    virtual void
    residual(const VectorType &x, VectorType &r) = 0;

    /**
     * Freeze the linearisation state at @p x. With @p monotone no
     * constraint is added (constraints may be released or tightened in
     * kind, e.g. from slip to stick), so that repeated updates end.
     */
    virtual Change
    update_linearization(const VectorType &x, const bool monotone) = 0;

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

    /**
     * Why the last residual evaluation was not finite, for the message of
     * a rejected step (e.g. "a material point inverts"), or empty if the
     * problem cannot tell. Collective.
     */
    virtual std::string
    why_not_finite() const
    {
      return "";
    }

    /** @p what, then ": " and why_not_finite() if it says why. Collective. */
    std::string
    not_finite(const std::string &what) const
    {
      const std::string reason = why_not_finite();
      return reason.empty() ? what : what + ": " + reason;
    }
  };



  /**
   * What one Newton solve did.
   */
  struct NewtonStatistics
  {
    bool        converged = false;
    std::string failure;
    /** The residual at the first iterate was not finite. */
    bool          failed_at_first_iterate = false;
    unsigned int  iterations              = 0;
    unsigned int  linear_iterations       = 0;
    unsigned int  status_changes          = 0;
    unsigned long residual_evaluations    = 0;
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
   * the velocity scale. With `Nonlinear solver/Verbose` each iteration
   * writes one line to the log stream of the owner, and each solve one
   * line with its result.
   */
  class NewtonKrylovSolver
  {
  public:
    using VectorType = NonlinearProblem::VectorType;

    /**
     * A solver with the given options and velocity scale U. The lines of
     * `Nonlinear solver/Verbose` go to @p log (the owner makes it active
     * on one rank only); the default stream prints nothing.
     */
    NewtonKrylovSolver(
      const NonlinearSolverParameters &nonlinear,
      const LinearSolverParameters    &linear,
      const double                     velocity_scale,
      const ConditionalOStream &log = ConditionalOStream(std::cout, false));

    /**
     * Solve R(@p x) = 0 from the initial guess @p x. On failure
     * `converged` is false, `failure` says why, and @p x is the last
     * iterate. @p cfl, the CFL number of the step, chooses the
     * preconditioner under `Preconditioner = automatic`.
     */
    NewtonStatistics
    solve(NonlinearProblem &problem,
          VectorType       &x,
          const double      cfl = 0.) const;

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
    /**
     * What the phases of one solve share: the scales of the stopping
     * test, the residual norms, the forcing term, the counters of the
     * current iteration and the work vectors.
     */
    struct IterationState
    {
      /** Work vectors with the layout of @p x. */
      explicit IterationState(const VectorType &x);

      /** ||R|| / F_scale at the current iterate. */
      double
      relative_norm() const
      {
        return scale > 0. ? norm / scale : 0.;
      }

      /** sqrt(number of unknowns). */
      double root_n = 0.;
      /** F_scale of the stopping test. */
      double scale = 0.;
      /**
       * ||R|| at which Newton stops: from the tolerance and the residual
       * scale (base_target), lowered by the motion tolerance at each
       * iterate.
       */
      double base_target = 0.;
      double target      = 0.;
      /** ||R|| at the current and at the previous iterate. */
      double norm          = 0.;
      double previous_norm = 0.;
      /** Relative tolerance of the current linear solve. */
      double eta = 0.;
      /** The iteration limit, possibly extended once. */
      unsigned int limit = 0;
      /** The contact status changed: the forcing term starts again. */
      bool restarted = false;
      /** The preconditioner is probed Jacobi. */
      bool probed = false;
      /** The preconditioner is the problem's assembled one. */
      bool assembled = false;
      /** The assembled preconditioner needs a new setup. */
      bool preconditioner_stale = false;
      /** Krylov iterations and line search halvings of this iteration. */
      unsigned int linear_iterations = 0;
      unsigned int cuts              = 0;

      /** R at the iterate, the trial point and its R, dx, -R, diagonal. */
      VectorType r, trial, trial_r, dx, rhs, diagonal;
    };

    /**
     * First linearisation and residual at @p x, the preconditioner for a
     * step of CFL number @p cfl, the scales of the stopping test, the
     * probed diagonal and the initial forcing term. Returns why the solve
     * cannot start, or an empty string.
     */
    std::string
    initialize(NonlinearProblem &problem,
               const VectorType &x,
               const double      cfl,
               IterationState   &state) const;

    /**
     * Whether iteration @p k is at the iteration limit, after extending
     * the limit once for a solve that contracts fast enough.
     */
    bool
    at_iteration_limit(const unsigned int k, IterationState &state) const;

    /** The forcing term eta of iteration @p k. */
    void
    update_forcing_term(const unsigned int k, IterationState &state) const;

    /**
     * J dx = -R at @p x with the configured Krylov solver and
     * preconditioner. Returns why the Krylov solver failed, or an empty
     * string (also when it stopped without reaching its tolerance).
     */
    std::string
    solve_linear_system(NonlinearProblem &problem,
                        const VectorType &x,
                        IterationState   &state) const;

    /**
     * Backtracking on ||R|| along dx with the frozen status, then @p x the
     * accepted point. Returns why no step was accepted, or an empty
     * string.
     */
    std::string
    line_search(NonlinearProblem &problem,
                VectorType       &x,
                IterationState   &state) const;

    /**
     * Re-evaluate the linearisation state at @p x (contact status) while
     * changes are allowed, and R with a changed one. Returns why the new
     * residual is unusable, or an empty string.
     */
    std::string
    update_status(NonlinearProblem &problem,
                  const VectorType &x,
                  IterationState   &state,
                  NewtonStatistics &statistics) const;

    /** The log line of the iterate after @p statistics.iterations. */
    void
    log_iteration(const NewtonStatistics &statistics,
                  const IterationState   &state) const;

    /** The log line of the result of the solve. */
    void
    log_result(const NewtonStatistics &statistics,
               const IterationState   &state) const;

    const NonlinearSolverParameters &nonlinear;
    const LinearSolverParameters    &linear;
    const double                     velocity_scale;
    const ConditionalOStream         iteration_log;
  };
} // namespace grainmpm

#endif
