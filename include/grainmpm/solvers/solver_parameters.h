// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_solvers_solver_parameters_h
#define grainmpm_solvers_solver_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace grainmpm
{
  /**
   * How the Newton residual is made dimensionless.
   */
  enum class ResidualScale
  {
    initial_residual,
    physical
  };

  /**
   * How the finite-difference step of the Jacobian-vector product is chosen
   * (the formulas are in the documentation of Nonlinear solver/Differencing
   * step).
   */
  enum class DifferencingStep
  {
    pernice_walker,
    knoll_keyes
  };

  /**
   * The relative tolerance of the linear solve of a Newton step.
   */
  enum class ForcingTerm
  {
    constant,
    eisenstat_walker
  };

  /**
   * Subsection "Nonlinear solver": the inexact Newton iteration of the
   * implicit scheme.
   */
  struct NonlinearSolverParameters
  {
    double        tolerance           = 1e-6;
    std::string   residual_scale_text = "initial residual";
    ResidualScale residual_scale      = ResidualScale::initial_residual;
    double        velocity_scale      = 0.;
    double        absolute_tolerance  = 1e-12;
    /**
     * Newton also needs RMS(R) below this times the largest speed of the
     * iterate (0: off).
     */
    double       motion_tolerance = 1e-5;
    unsigned int max_iterations   = 20;
    std::string  forcing_text     = "Eisenstat-Walker";
    ForcingTerm  forcing          = ForcingTerm::eisenstat_walker;
    /** Set by check(): forcing is Eisenstat-Walker. */
    bool             eisenstat_walker     = true;
    double           forcing_constant     = 1e-2;
    double           forcing_maximum      = 0.9;
    double           forcing_gamma        = 0.9;
    double           forcing_alpha        = 2.;
    std::string      differencing_text    = "Pernice-Walker";
    DifferencingStep differencing         = DifferencingStep::pernice_walker;
    double           differencing_error   = 0.;
    bool             line_search          = true;
    unsigned int     max_line_search_cuts = 10;
    unsigned int     max_status_changes   = 10;
    /** Hysteresis band of the contact status, in units of U. */
    double status_tolerance = 0.;
    /** The first status of a step starts from the last step's. */
    bool keep_contact_status = true;
    /** One screen line per Newton iteration and per solve. */
    bool verbose = false;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * The Krylov solvers of the Newton steps.
   */
  enum class KrylovSolver
  {
    gmres,
    fgmres
  };

  /**
   * The preconditioners of the Krylov solver.
   */
  enum class Preconditioner
  {
    none,
    probed_jacobi,
    amg,
    sparse_cholesky,
    /**
     * Probed Jacobi for steps up to LinearSolverParameters::automatic_cfl,
     * the assembled matrix for longer ones: sparse Cholesky on one MPI
     * process, AMG on more.
     */
    automatic
  };

  /**
   * Subsection "Linear solver": the Krylov solver of each Newton step and
   * its preconditioner.
   */
  struct LinearSolverParameters
  {
    std::string  solver_text = "GMRES";
    KrylovSolver solver      = KrylovSolver::gmres;
    /** Set by check(): solver is FGMRES. */
    bool           flexible            = false;
    unsigned int   restart_length      = 30;
    unsigned int   max_iterations      = 200;
    std::string    preconditioner_text = "automatic";
    Preconditioner preconditioner      = Preconditioner::automatic;
    /**
     * With Preconditioner::automatic, the CFL number c dt / h of a step
     * above which the assembled matrix preconditions it.
     */
    double       automatic_cfl = 5.;
    double       jacobi_weight = 1.;
    unsigned int jacobi_sweeps = 1;

    void
    declare(ParameterHandler &prm);
    void
    check();

    /** Whether a step of CFL number @p cfl is preconditioned by probed Jacobi. */
    bool
    probed_jacobi_at(const double cfl) const
    {
      return preconditioner == Preconditioner::probed_jacobi ||
             (preconditioner == Preconditioner::automatic &&
              cfl <= automatic_cfl);
    }

    /**
     * Whether a step of CFL number @p cfl is preconditioned by the
     * assembled matrix (AMG or sparse Cholesky).
     */
    bool
    assembled_at(const double cfl) const
    {
      return preconditioner == Preconditioner::amg ||
             preconditioner == Preconditioner::sparse_cholesky ||
             (preconditioner == Preconditioner::automatic &&
              cfl > automatic_cfl);
    }
  };
} // namespace grainmpm

#endif
