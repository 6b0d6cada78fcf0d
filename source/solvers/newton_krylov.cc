// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/solvers/newton_krylov.h>

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    using VectorType = NonlinearProblem::VectorType;

    /**
     * J z by finite differences at a fixed point x with R(x) = r: the
     * matrix of the Krylov solvers.
     */
    class FiniteDifferenceJacobian
    {
    public:
      FiniteDifferenceJacobian(NonlinearProblem         &problem,
                               const NewtonKrylovSolver &solver,
                               const VectorType         &x,
                               const VectorType         &r)
        : problem(problem)
        , solver(solver)
        , x(x)
        , r(r)
      {}

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        solver.jacobian_vmult(problem, x, r, src, dst);
      }

    private:
      NonlinearProblem         &problem;
      const NewtonKrylovSolver &solver;
      const VectorType         &x;
      const VectorType         &r;
    };



    /**
     * The problem's assembled preconditioner
     * (NonlinearProblem::apply_preconditioner()).
     */
    class AssembledPreconditioner
    {
    public:
      explicit AssembledPreconditioner(NonlinearProblem &problem)
        : problem(problem)
      {}

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        problem.apply_preconditioner(dst, src);
      }

    private:
      NonlinearProblem &problem;
    };



    /**
     * Weighted Jacobi: z = omega D^-1 r, then sweeps - 1 times
     * z += omega D^-1 (r - J z).
     */
    class JacobiPreconditioner
    {
    public:
      JacobiPreconditioner(const FiniteDifferenceJacobian &jacobian,
                           const VectorType               &diagonal,
                           const double                    weight,
                           const unsigned int              sweeps)
        : jacobian(jacobian)
        , weight(weight)
        , sweeps(sweeps)
      {
        inverse_diagonal.reinit(diagonal, true);
        for (unsigned int k = 0; k < diagonal.locally_owned_size(); ++k)
          {
            const double d = diagonal.local_element(k);
            // A row that probing could not see (or saw as singular) keeps
            // the identity.
            inverse_diagonal.local_element(k) =
              (std::isfinite(d) && std::abs(d) > 1e-12) ? 1. / d : 1.;
          }
        if (sweeps > 1)
          {
            work.reinit(diagonal, true);
            product.reinit(diagonal, true);
          }
      }

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        dst = src;
        dst.scale(inverse_diagonal);
        dst *= weight;
        for (unsigned int sweep = 1; sweep < sweeps; ++sweep)
          {
            jacobian.vmult(product, dst);
            work = src;
            work -= product;
            work.scale(inverse_diagonal);
            dst.add(weight, work);
          }
      }

    private:
      const FiniteDifferenceJacobian &jacobian;
      VectorType                      inverse_diagonal;
      const double                    weight;
      const unsigned int              sweeps;
      mutable VectorType              work;
      mutable VectorType              product;
    };



    bool
    is_finite(const VectorType &v)
    {
      return std::isfinite(v.l2_norm());
    }


    /** The preconditioner a Krylov solve applies, and what it needs. */
    struct Preconditioning
    {
      NonlinearProblem             &problem;
      const VectorType             &diagonal;
      const LinearSolverParameters &linear;
      const bool                    probed;
      const bool                    assembled;
    };



    /**
     * @p solver on J @p dx = @p rhs with the configured preconditioner:
     * weighted Jacobi with @p jacobi_sweeps sweeps, the problem's
     * assembled one, or none.
     */
    template <typename SolverType>
    void
    solve_preconditioned(SolverType                     &solver,
                         const FiniteDifferenceJacobian &jacobian,
                         VectorType                     &dx,
                         const VectorType               &rhs,
                         const Preconditioning          &preconditioning,
                         const unsigned int              jacobi_sweeps)
    {
      if (preconditioning.probed)
        solver.solve(jacobian,
                     dx,
                     rhs,
                     JacobiPreconditioner(jacobian,
                                          preconditioning.diagonal,
                                          preconditioning.linear.jacobi_weight,
                                          jacobi_sweeps));
      else if (preconditioning.assembled)
        solver.solve(jacobian,
                     dx,
                     rhs,
                     AssembledPreconditioner(preconditioning.problem));
      else
        solver.solve(jacobian, dx, rhs, PreconditionIdentity());
    }

  } // namespace



  NewtonKrylovSolver::NewtonKrylovSolver(
    const NonlinearSolverParameters &nonlinear,
    const LinearSolverParameters    &linear,
    const double                     velocity_scale,
    const ConditionalOStream        &log)
    : nonlinear(nonlinear)
    , linear(linear)
    , velocity_scale(velocity_scale)
    , iteration_log(log)
  {}



  double
  NewtonKrylovSolver::differencing_step(const VectorType &x,
                                        const VectorType &z) const
  {
    // Velocities are made dimensionless by U; eps z is then a velocity
    // perturbation of dimensionless size sqrt(e (1 + ||x / U||)) (Pernice
    // and Walker), or of root-mean-square size sqrt(e) (mean |x / U| + 1)
    // (Knoll and Keyes' averaged form).
    const double z_norm = z.l2_norm();
    const double e      = nonlinear.differencing_error;
    if (nonlinear.differencing == DifferencingStep::pernice_walker)
      return std::sqrt(e * (1. + x.l2_norm() / velocity_scale)) *
             velocity_scale / z_norm;
    const double n = static_cast<double>(x.size());
    return std::sqrt(e) * (x.l1_norm() / n + velocity_scale) * std::sqrt(n) /
           z_norm;
  }



  void
  NewtonKrylovSolver::jacobian_vmult(NonlinearProblem &problem,
                                     const VectorType &x,
                                     const VectorType &r,
                                     const VectorType &z,
                                     VectorType       &jz) const
  {
    if (z.l2_norm() == 0.)
      {
        jz.reinit(r, true);
        jz = 0.;
        return;
      }
    const double eps = differencing_step(x, z);
    VectorType   perturbed(x);
    perturbed.add(eps, z);
    jz.reinit(r, true);
    problem.residual(perturbed, jz);
    jz -= r;
    jz /= eps;
  }



  NewtonKrylovSolver::IterationState::IterationState(const VectorType &x)
    : r(x)
    , trial(x)
    , trial_r(x)
    , dx(x)
    , rhs(x)
  {}



  NewtonStatistics
  NewtonKrylovSolver::solve(NonlinearProblem &problem,
                            VectorType       &x,
                            const double      cfl) const
  {
    NewtonStatistics    statistics;
    const unsigned long evaluations_at_start = problem.n_residual_evaluations();
    IterationState      state(x);
    const auto finish = [&](const bool converged, const std::string &why) {
      statistics.converged = converged;
      statistics.failure   = why;
      statistics.residual_evaluations =
        problem.n_residual_evaluations() - evaluations_at_start;
      log_result(statistics, state);
      return statistics;
    };

    std::string why = initialize(problem, x, cfl, state);
    if (!why.empty())
      {
        statistics.failed_at_first_iterate = true;
        return finish(false, why);
      }
    log_iteration(statistics, state);
    for (unsigned int k = 0;; ++k)
      {
        statistics.residual_norm = state.norm / (state.root_n * velocity_scale);
        if (nonlinear.motion_tolerance > 0.)
          state.target = std::max(std::min(state.base_target,
                                           nonlinear.motion_tolerance *
                                             state.root_n * x.linfty_norm()),
                                  nonlinear.absolute_tolerance *
                                    velocity_scale * state.root_n);
        if (state.norm <= state.target)
          return finish(true, "");
        if (at_iteration_limit(k, state))
          {
            std::ostringstream message;
            message << "Newton did not converge in " << k
                    << " iterations (||R|| / F_scale = " << std::setprecision(2)
                    << state.relative_norm() << ", tolerance "
                    << nonlinear.tolerance << ")";
            return finish(false, message.str());
          }
        update_forcing_term(k, state);
        why = solve_linear_system(problem, x, state);
        statistics.linear_iterations += state.linear_iterations;
        if (why.empty())
          why = line_search(problem, x, state);
        if (why.empty())
          {
            ++statistics.iterations;
            why = update_status(problem, x, state, statistics);
          }
        if (!why.empty())
          return finish(false, why);
        log_iteration(statistics, state);
      }
  }



  std::string
  NewtonKrylovSolver::initialize(NonlinearProblem &problem,
                                 const VectorType &x,
                                 const double      cfl,
                                 IterationState   &state) const
  {
    problem.update_linearization(x, false);
    problem.residual(x, state.r);
    state.norm = state.r.l2_norm();
    if (!std::isfinite(state.norm))
      return problem.not_finite(
        "the residual of the initial guess is not finite");

    state.root_n = std::sqrt(static_cast<double>(x.size()));
    state.scale  = (nonlinear.residual_scale == ResidualScale::physical) ?
                     state.root_n * velocity_scale :
                     state.norm;
    state.base_target =
      std::max(nonlinear.tolerance * state.scale,
               nonlinear.absolute_tolerance * velocity_scale * state.root_n);
    state.target = state.base_target;

    state.probed    = linear.probed_jacobi_at(cfl);
    state.assembled = linear.assembled_at(cfl);
    if (state.probed && state.norm > state.target)
      problem.jacobian_diagonal(
        x,
        [this](const VectorType &a, const VectorType &b) {
          return differencing_step(a, b);
        },
        state.diagonal);

    // The assembled preconditioner depends on the contact status: set up
    // before the first linear solve and again after each change of it.
    state.preconditioner_stale = state.assembled;

    state.previous_norm = state.norm;
    state.restarted     = false;
    state.limit         = nonlinear.max_iterations;
    state.eta           = nonlinear.forcing_constant;
    return "";
  }



  bool
  NewtonKrylovSolver::at_iteration_limit(const unsigned int k,
                                         IterationState    &state) const
  {
    // A solve that reaches the iteration limit still contracting fast
    // enough to converge within a quarter more iterations (at the rate of
    // its last iteration) is given them once, instead of throwing the step
    // away just above the tolerance.
    if (k == state.limit && state.limit == nonlinear.max_iterations && k > 0 &&
        state.norm < 0.5 * state.previous_norm)
      {
        const unsigned int extra = std::max(1U, nonlinear.max_iterations / 4);
        if (std::log(state.target / state.norm) /
              std::log(state.norm / state.previous_norm) <=
            extra)
          state.limit += extra;
      }
    return k == state.limit;
  }



  void
  NewtonKrylovSolver::update_forcing_term(const unsigned int k,
                                          IterationState    &state) const
  {
    // Constant, or Eisenstat-Walker choice 2 with its safeguard; never
    // below what the Newton tolerance needs (solve_linear_system()). After
    // a change of the contact status the residual belongs to another
    // linearisation, and the ratio of EW would be that of two problems (a
    // rise gave eta = 0.9, one GMRES iteration, a poor iterate and a
    // status decided on it, so that hundreds of slots flipped on and off
    // from iteration to iteration): the forcing starts again from the
    // constant one. Not after a change of slip directions only: with
    // friction those change at almost every iteration, and accurate steps
    // then made them swing (the frictional two-disk collision no longer
    // converged).
    if (k > 0 && nonlinear.eisenstat_walker && !state.restarted)
      {
        const double safeguard = nonlinear.forcing_gamma *
                                 std::pow(state.eta, nonlinear.forcing_alpha);
        state.eta =
          nonlinear.forcing_gamma *
          std::pow(state.norm / state.previous_norm, nonlinear.forcing_alpha);
        if (safeguard > 0.1)
          state.eta = std::max(state.eta, safeguard);
        state.eta = std::min(state.eta, nonlinear.forcing_maximum);
      }
    else if (!nonlinear.eisenstat_walker || state.restarted)
      state.eta = nonlinear.forcing_constant;
    state.restarted = false;
  }



  std::string
  NewtonKrylovSolver::solve_linear_system(NonlinearProblem &problem,
                                          const VectorType &x,
                                          IterationState   &state) const
  {
    state.linear_iterations = 0;
    const double linear_tolerance =
      std::max(state.eta * state.norm, 0.5 * state.target);
    if (state.preconditioner_stale)
      {
        problem.setup_preconditioner(x);
        state.preconditioner_stale = false;
      }

    // J dx = -R, matrix-free, from dx = 0.
    const FiniteDifferenceJacobian jacobian(problem, *this, x, state.r);
    SolverControl                  control(linear.max_iterations,
                          linear_tolerance,
                          false,
                          false);
    state.dx  = 0.;
    state.rhs = state.r;
    state.rhs *= -1.;
    const Preconditioning preconditioning{
      problem, state.diagonal, linear, state.probed, state.assembled};
    try
      {
        if (linear.flexible)
          {
            SolverFGMRES<VectorType> fgmres(
              control,
              typename SolverFGMRES<VectorType>::AdditionalData(
                linear.restart_length));
            solve_preconditioned(fgmres,
                                 jacobian,
                                 state.dx,
                                 state.rhs,
                                 preconditioning,
                                 linear.jacobi_sweeps);
          }
        else
          {
            SolverGMRES<VectorType> gmres(
              control,
              typename SolverGMRES<VectorType>::AdditionalData(
                linear.restart_length + 2, true));
            solve_preconditioned(
              gmres, jacobian, state.dx, state.rhs, preconditioning, 1);
          }
      }
    catch (const SolverControl::NoConvergence &)
      {
        // Inexact Newton goes on with the best direction found; the line
        // search decides whether it is good enough.
      }
    catch (const std::exception &exception)
      {
        return std::string("the Krylov solver failed: ") + exception.what();
      }
    state.linear_iterations = control.last_step();
    if (!is_finite(state.dx))
      return "the Newton direction is not finite";
    return "";
  }



  std::string
  NewtonKrylovSolver::line_search(NonlinearProblem &problem,
                                  VectorType       &x,
                                  IterationState   &state) const
  {
    // Backtracking on ||R|| with the frozen status.
    double       lambda   = 1.;
    double       new_norm = 0.;
    unsigned int cuts     = 0;
    for (;; ++cuts)
      {
        state.trial = x;
        state.trial.add(lambda, state.dx);
        problem.residual(state.trial, state.trial_r);
        new_norm = state.trial_r.l2_norm();
        if (std::isfinite(new_norm) &&
            (!nonlinear.line_search ||
             new_norm <= (1. - 1e-4 * lambda * (1. - state.eta)) * state.norm))
          break;
        if (cuts == nonlinear.max_line_search_cuts || !nonlinear.line_search)
          {
            std::ostringstream why;
            why << "the line search found no decrease of ||R|| after " << cuts
                << " halvings (||R|| / F_scale = " << state.relative_norm()
                << ")";
            return why.str();
          }
        lambda *= 0.5;
      }
    x                   = state.trial;
    state.r             = state.trial_r;
    state.previous_norm = state.norm;
    state.norm          = new_norm;
    state.cuts          = cuts;
    return "";
  }



  std::string
  NewtonKrylovSolver::update_status(NonlinearProblem &problem,
                                    const VectorType &x,
                                    IterationState   &state,
                                    NewtonStatistics &statistics) const
  {
    // Re-evaluate the contact status after every iteration: a primal-dual
    // active set, whose converged status is consistent with the converged
    // velocities (no constraint pulls, no free slot passes its bound).
    // After Maximum contact status changes discrete changes no constraint
    // is added any more, so that a status that would cycle settles.
    const NonlinearProblem::Change change = problem.update_linearization(
      x, statistics.status_changes >= nonlinear.max_status_changes);
    if (change == NonlinearProblem::Change::discrete ||
        change == NonlinearProblem::Change::minor)
      {
        ++statistics.status_changes;
        state.restarted = true;
        if (change == NonlinearProblem::Change::discrete)
          state.preconditioner_stale = state.assembled;
      }
    if (change != NonlinearProblem::Change::none)
      {
        problem.residual(x, state.r);
        state.norm = state.r.l2_norm();
        if (!std::isfinite(state.norm))
          return problem.not_finite(
            "the residual is not finite after a change of the contact status");
      }
    return "";
  }



  void
  NewtonKrylovSolver::log_iteration(const NewtonStatistics &statistics,
                                    const IterationState   &state) const
  {
    if (!iteration_log.is_active())
      return;
    std::ostringstream line;
    line << "  Newton " << std::setw(3) << statistics.iterations
         << ": |R|/F = " << std::scientific << std::setprecision(3)
         << state.relative_norm();
    if (statistics.iterations > 0)
      line << "  eta = " << std::setprecision(1) << state.eta << "  "
           << (linear.flexible ? "FGMRES " : "GMRES ")
           << state.linear_iterations << "  line search " << state.cuts
           << "  status changes " << statistics.status_changes;
    iteration_log << line.str() << std::endl;
  }



  void
  NewtonKrylovSolver::log_result(const NewtonStatistics &statistics,
                                 const IterationState   &state) const
  {
    if (!iteration_log.is_active())
      return;
    std::ostringstream line;
    line << "  Newton "
         << (statistics.converged ? "converged in " : "failed after ")
         << statistics.iterations << " iterations: |R|/F = " << std::scientific
         << std::setprecision(3) << state.relative_norm() << ", "
         << statistics.linear_iterations << " Krylov iterations, "
         << statistics.residual_evaluations << " residual evaluations";
    if (!statistics.converged)
      line << " (" << statistics.failure << ")";
    iteration_log << line.str() << std::endl;
  }
} // namespace grainmpm
