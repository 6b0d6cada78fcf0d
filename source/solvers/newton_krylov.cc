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
  } // namespace



  NewtonKrylovSolver::NewtonKrylovSolver(
    const NonlinearSolverParameters &nonlinear,
    const LinearSolverParameters    &linear,
    const double                     velocity_scale)
    : nonlinear(nonlinear)
    , linear(linear)
    , velocity_scale(velocity_scale)
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



  NewtonStatistics
  NewtonKrylovSolver::solve(NonlinearProblem &problem, VectorType &x) const
  {
    NewtonStatistics    statistics;
    const unsigned long evaluations_at_start = problem.n_residual_evaluations();
    const auto finish = [&](const bool converged, const std::string &why) {
      statistics.converged = converged;
      statistics.failure   = why;
      statistics.residual_evaluations =
        problem.n_residual_evaluations() - evaluations_at_start;
      return statistics;
    };

    VectorType r(x), trial(x), trial_r(x), dx(x), rhs(x), diagonal;
    problem.update_linearization(x);
    problem.residual(x, r);
    double norm = r.l2_norm();
    if (!std::isfinite(norm))
      return finish(false, "the residual of the initial guess is not finite");

    const double root_n = std::sqrt(static_cast<double>(x.size()));
    const double scale = (nonlinear.residual_scale == ResidualScale::physical) ?
                           root_n * velocity_scale :
                           norm;
    const double target =
      std::max(nonlinear.tolerance * scale,
               nonlinear.absolute_tolerance * velocity_scale * root_n);
    const auto relative = [&](const double value) {
      return scale > 0. ? value / scale : 0.;
    };

    if (linear.probed_jacobi && norm > target)
      problem.jacobian_diagonal(
        x,
        [this](const VectorType &a, const VectorType &b) {
          return differencing_step(a, b);
        },
        diagonal);

    // The assembled preconditioner depends on the contact status: set up
    // before the first linear solve and again after each change of it.
    const bool assembled = (linear.preconditioner == Preconditioner::amg);
    bool       preconditioner_stale = assembled;

    double       previous_norm = norm;
    bool         restarted     = false;
    unsigned int limit         = nonlinear.max_iterations;
    double       eta           = nonlinear.forcing_constant;
    for (unsigned int k = 0;; ++k)
      {
        statistics.residual_norm = norm / (root_n * velocity_scale);
        if (norm <= target)
          return finish(true, "");
        // A solve that reaches the iteration limit still contracting fast
        // enough to converge within a quarter more iterations (at the
        // rate of its last iteration) is given them once, instead of
        // throwing the step away just above the tolerance.
        if (k == limit && limit == nonlinear.max_iterations && k > 0 &&
            norm < 0.5 * previous_norm)
          {
            const unsigned int extra =
              std::max(1U, nonlinear.max_iterations / 4);
            if (std::log(target / norm) / std::log(norm / previous_norm) <=
                extra)
              limit += extra;
          }
        if (k == limit)
          {
            std::ostringstream why;
            why << "Newton did not converge in " << k
                << " iterations (||R|| / F_scale = " << std::setprecision(2)
                << relative(norm) << ", tolerance " << nonlinear.tolerance
                << ")";
            return finish(false, why.str());
          }

        // Forcing term: constant, or Eisenstat-Walker choice 2 with its
        // safeguard; never below what the Newton tolerance needs. After a
        // change of the contact status the residual belongs to another
        // linearisation, and the ratio of EW would be that of two problems
        // (a rise gave eta = 0.9, one GMRES iteration, a poor iterate and
        // a status decided on it, so that hundreds of slots flipped on
        // and off from iteration to iteration): the forcing starts again
        // from the constant one. Not after a change of slip directions
        // only: with friction those change at almost every iteration, and
        // accurate steps then made them swing (the frictional two-disk
        // collision no longer converged).
        if (k > 0 && nonlinear.eisenstat_walker && !restarted)
          {
            const double safeguard =
              nonlinear.forcing_gamma * std::pow(eta, nonlinear.forcing_alpha);
            eta = nonlinear.forcing_gamma *
                  std::pow(norm / previous_norm, nonlinear.forcing_alpha);
            if (safeguard > 0.1)
              eta = std::max(eta, safeguard);
            eta = std::min(eta, nonlinear.forcing_maximum);
          }
        else if (!nonlinear.eisenstat_walker || restarted)
          eta = nonlinear.forcing_constant;
        restarted                     = false;
        const double linear_tolerance = std::max(eta * norm, 0.5 * target);

        if (preconditioner_stale)
          {
            problem.setup_preconditioner(x);
            preconditioner_stale = false;
          }

        // J dx = -R, matrix-free, from dx = 0.
        const FiniteDifferenceJacobian jacobian(problem, *this, x, r);
        SolverControl                  control(linear.max_iterations,
                              linear_tolerance,
                              false,
                              false);
        dx  = 0.;
        rhs = r;
        rhs *= -1.;
        try
          {
            if (linear.flexible)
              {
                SolverFGMRES<VectorType> fgmres(
                  control,
                  typename SolverFGMRES<VectorType>::AdditionalData(
                    linear.restart_length));
                if (linear.probed_jacobi)
                  fgmres.solve(jacobian,
                               dx,
                               rhs,
                               JacobiPreconditioner(jacobian,
                                                    diagonal,
                                                    linear.jacobi_weight,
                                                    linear.jacobi_sweeps));
                else if (assembled)
                  fgmres.solve(jacobian,
                               dx,
                               rhs,
                               AssembledPreconditioner(problem));
                else
                  fgmres.solve(jacobian, dx, rhs, PreconditionIdentity());
              }
            else
              {
                SolverGMRES<VectorType> gmres(
                  control,
                  typename SolverGMRES<VectorType>::AdditionalData(
                    linear.restart_length + 2, true));
                if (linear.probed_jacobi)
                  gmres.solve(jacobian,
                              dx,
                              rhs,
                              JacobiPreconditioner(
                                jacobian, diagonal, linear.jacobi_weight, 1));
                else if (assembled)
                  gmres.solve(jacobian,
                              dx,
                              rhs,
                              AssembledPreconditioner(problem));
                else
                  gmres.solve(jacobian, dx, rhs, PreconditionIdentity());
              }
          }
        catch (const SolverControl::NoConvergence &)
          {
            // Inexact Newton goes on with the best direction found; the
            // line search decides whether it is good enough.
          }
        catch (const std::exception &exception)
          {
            return finish(false,
                          std::string("the Krylov solver failed: ") +
                            exception.what());
          }
        statistics.linear_iterations += control.last_step();
        if (!is_finite(dx))
          return finish(false, "the Newton direction is not finite");

        // Backtracking on ||R|| with the frozen status.
        double       lambda   = 1.;
        double       new_norm = 0.;
        unsigned int cuts     = 0;
        for (;; ++cuts)
          {
            trial = x;
            trial.add(lambda, dx);
            problem.residual(trial, trial_r);
            new_norm = trial_r.l2_norm();
            if (std::isfinite(new_norm) &&
                (!nonlinear.line_search ||
                 new_norm <= (1. - 1e-4 * lambda * (1. - eta)) * norm))
              break;
            if (cuts == nonlinear.max_line_search_cuts ||
                !nonlinear.line_search)
              {
                std::ostringstream why;
                why << "the line search found no decrease of ||R|| after "
                    << cuts << " halvings (||R|| / F_scale = " << relative(norm)
                    << ")";
                return finish(false, why.str());
              }
            lambda *= 0.5;
          }
        x             = trial;
        r             = trial_r;
        previous_norm = norm;
        norm          = new_norm;
        ++statistics.iterations;

        // Re-evaluate the contact status between iterations (at most
        // Maximum contact status changes discrete changes).
        if (statistics.status_changes < nonlinear.max_status_changes)
          {
            const NonlinearProblem::Change change =
              problem.update_linearization(x);
            if (change == NonlinearProblem::Change::discrete)
              {
                ++statistics.status_changes;
                restarted            = true;
                preconditioner_stale = assembled;
              }
            if (change != NonlinearProblem::Change::none)
              {
                problem.residual(x, r);
                norm = r.l2_norm();
                if (!std::isfinite(norm))
                  return finish(false, "the residual is not finite");
              }
          }
      }
  }
} // namespace grainmpm
