// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/solvers/solver_parameters.h>

#include <deal.II/base/patterns.h>

#include <limits>
#include <sstream>

namespace grainmpm
{
  // ----------------------------------------------------- nonlinear solver

  void
  NonlinearSolverParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.add_parameter(
      "Tolerance",
      tolerance,
      "Newton stops when ||R|| / F_scale is below this value, R being the "
      "residual of eq. 16 of Cummins & Brackbill divided by the slot mass "
      "(velocity units) in the Euclidean norm. Dimensionless.",
      Patterns::Double(1e-14, 1.));
    prm.add_parameter(
      "Residual scale",
      residual_scale_text,
      "F_scale: 'initial residual' (the norm of R at the initial guess of "
      "the step) or 'physical' (sqrt(number of unknowns) times Velocity "
      "scale, so that the tolerance is a root-mean-square velocity error "
      "relative to Velocity scale). Dimensionless.",
      Patterns::Selection("initial residual|physical"));
    prm.add_parameter(
      "Velocity scale",
      velocity_scale,
      "The velocity that makes velocities dimensionless for the 'physical' "
      "residual scale and the finite-difference step. Zero means the "
      "largest dilatational wave speed of the materials. Units: "
      "length/time.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Absolute tolerance",
      absolute_tolerance,
      "Newton also stops when the root-mean-square of R is below this "
      "value times Velocity scale, so that steps that start at equilibrium "
      "converge. Dimensionless.",
      Patterns::Double(0., 1.));
    prm.add_parameter(
      "Motion tolerance",
      motion_tolerance,
      "Newton also needs the root-mean-square of R to be below this value "
      "times the largest speed of the iterate (any slot, rigid grains "
      "included), so that the velocity error is small against the motion "
      "even where the initial residual is large against it: with contact "
      "at steps many times the explicit one under slow loading, a relative "
      "Tolerance of 1e-6 of the initial residual left errors of 10 % of "
      "the platen speed, which created energy, and 1e-4 still let a "
      "jammed stack under Newton steps preconditioned by the assembled "
      "matrix gain 2.6 % of the platen work (doc/theory.md section 10). "
      "Absolute tolerance stays the floor. Zero turns the test off. "
      "Dimensionless.",
      Patterns::Double(0., 1.));
    prm.add_parameter("Maximum Newton iterations",
                      max_iterations,
                      "Newton iterations per step; a step that has not "
                      "converged then is rejected (see Time stepping/"
                      "Adaptive time stepping), unless its last iteration "
                      "contracted ||R|| fast enough to reach the tolerance "
                      "within a quarter more iterations: those it is given "
                      "once. Dimensionless.",
                      Patterns::Integer(1, 1000));
    prm.add_parameter(
      "Forcing term",
      forcing_text,
      "Relative tolerance eta_k of the linear solve of Newton step k: "
      "'constant' (Forcing constant) or 'Eisenstat-Walker' (choice 2: "
      "gamma (||R_k|| / ||R_k-1||)^alpha with the usual safeguards, "
      "bounded by Maximum forcing term). Dimensionless.",
      Patterns::Selection("constant|Eisenstat-Walker"));
    prm.add_parameter("Forcing constant",
                      forcing_constant,
                      "eta of the 'constant' forcing term, and eta_0 of "
                      "Eisenstat-Walker. Dimensionless.",
                      Patterns::Double(1e-12, 0.99));
    prm.add_parameter("Maximum forcing term",
                      forcing_maximum,
                      "Upper bound of the Eisenstat-Walker eta_k. "
                      "Dimensionless.",
                      Patterns::Double(1e-12, 0.99));
    prm.add_parameter("Eisenstat-Walker gamma",
                      forcing_gamma,
                      "gamma of Eisenstat-Walker choice 2. Dimensionless.",
                      Patterns::Double(0., 1.));
    prm.add_parameter("Eisenstat-Walker alpha",
                      forcing_alpha,
                      "alpha of Eisenstat-Walker choice 2. Dimensionless.",
                      Patterns::Double(1., 2.));
    prm.add_parameter(
      "Differencing step",
      differencing_text,
      "Step eps of the finite-difference Jacobian-vector product J z = "
      "(R(v + eps z) - R(v)) / eps, with velocities made dimensionless by "
      "Velocity scale: 'Pernice-Walker' eps = sqrt(e (1 + ||v||)) / ||z|| "
      "or 'Knoll-Keyes' eps = (e^(1/2) / (N ||z||)) sum_i |v_i| + e^(1/2), "
      "e being Differencing error. Dimensionless.",
      Patterns::Selection("Pernice-Walker|Knoll-Keyes"));
    prm.add_parameter("Differencing error",
                      differencing_error,
                      "Relative error e of a residual evaluation used in the "
                      "differencing step. Zero means the machine epsilon "
                      "2.2e-16. Dimensionless.",
                      Patterns::Double(0., 1e-2));
    prm.add_parameter("Line search",
                      line_search,
                      "Backtrack along the Newton direction (halving the "
                      "step) until ||R|| decreases sufficiently.");
    prm.add_parameter("Maximum line search cuts",
                      max_line_search_cuts,
                      "Halvings of the Newton step before the step is "
                      "rejected. Dimensionless.",
                      Patterns::Integer(0, 60));
    prm.add_parameter(
      "Maximum contact status changes",
      max_status_changes,
      "The contact status (which grains touch, stick or slip) is frozen "
      "within a Newton iteration and re-evaluated after every iteration (a "
      "primal-dual active set): a constraint whose reaction would pull is "
      "released, a free field that would pass the approach its gap allows "
      "is caught. A contact that has been caught or released four times in "
      "a step is not caught again, and one that has changed between "
      "sticking and sliding twice does not slip again; after this many "
      "changes of the whole status in one step, every contact may only be "
      "released or stick, so that a status that would cycle settles. "
      "Dimensionless.",
      Patterns::Integer(0, 100));
    prm.add_parameter(
      "Contact status from last step",
      keep_contact_status,
      "Whether the contact status of a step starts from the one the last "
      "step converged to: the contacts and wall contacts that held at its "
      "end are held at the first iterate, and are released there if their "
      "reaction would pull, while the others are caught if they pass the "
      "approach their gap allows. Otherwise every step decides its status "
      "afresh at the first iterate, on the velocities the momentum balance "
      "asks for, which at a long step catches and releases many slots that "
      "the solve then has to undo. Under slow loading the status changes "
      "little from one step to the next, and starting from it saves Newton "
      "iterations and rejected steps (doc/theory.md section 9.4). "
      "The retries of a rejected step start from it too, unless the "
      "residual with it was not finite at the first iterate or the step "
      "failed twice. The status is kept in checkpoints. The first step of "
      "a run, a step after one that ended with nothing held and the step "
      "after an explicit fallback decide afresh.",
      Patterns::Bool());
    prm.add_parameter(
      "Contact status tolerance",
      status_tolerance,
      "Hysteresis of the contact status between Newton iterations, in "
      "units of the velocity scale U: a slot held by contact or a wall is "
      "released only when it separates faster than this, a free slot is "
      "caught only when it approaches faster than this, and stick and "
      "slip change likewise only beyond it. Slots whose approach speed "
      "hovers about zero (grains resting on each other) then do not make "
      "the status chatter; the constraint may keep a pull of that speed "
      "times the slot mass. Zero: no hysteresis. Dimensionless.",
      Patterns::Double(0., 1e-2));
    prm.add_parameter(
      "Verbose",
      verbose,
      "Print one line per Newton iteration on the screen (first MPI rank; "
      "not with grainmpm --quiet): "
      "the iteration, ||R|| / F_scale after it (iteration 0: at the initial "
      "guess), the forcing term eta, the Krylov iterations, the line "
      "search halvings and the contact status changes so far in the step; "
      "and one line with the result of each Newton solve.");
    prm.leave_subsection();
  }



  void
  NonlinearSolverParameters::check()
  {
    const std::string entry = "Nonlinear solver/";
    residual_scale          = parse_choice<ResidualScale>(
      entry + "Residual scale = " + residual_scale_text,
      residual_scale_text,
      {{"initial residual", ResidualScale::initial_residual},
                {"physical", ResidualScale::physical}});
    forcing =
      parse_choice<ForcingTerm>(entry + "Forcing term = " + forcing_text,
                                forcing_text,
                                {{"constant", ForcingTerm::constant},
                                 {"Eisenstat-Walker",
                                  ForcingTerm::eisenstat_walker}});
    eisenstat_walker = (forcing == ForcingTerm::eisenstat_walker);
    differencing     = parse_choice<DifferencingStep>(
      entry + "Differencing step = " + differencing_text,
      differencing_text,
      {{"Pernice-Walker", DifferencingStep::pernice_walker},
           {"Knoll-Keyes", DifferencingStep::knoll_keyes}});
    if (differencing_error == 0.)
      differencing_error = std::numeric_limits<double>::epsilon();
    if (forcing_constant > forcing_maximum && eisenstat_walker)
      throw InputError("Nonlinear solver/Forcing constant",
                       "must not exceed Maximum forcing term.");
  }



  // -------------------------------------------------------- linear solver

  void
  LinearSolverParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.add_parameter(
      "Solver",
      solver_text,
      "Krylov solver of each Newton step J dv = -R: 'GMRES' (deal.II "
      "SolverGMRES with right preconditioning, eq. 17 of Cummins & "
      "Brackbill) or 'FGMRES' (SolverFGMRES, needed when the preconditioner "
      "varies, i.e. more than one Jacobi sweep). Dimensionless.",
      Patterns::Selection("GMRES|FGMRES"));
    prm.add_parameter("Restart length",
                      restart_length,
                      "Krylov vectors kept before GMRES restarts (the cost of "
                      "orthogonalisation grows with it). Dimensionless.",
                      Patterns::Integer(1, 500));
    prm.add_parameter("Maximum linear iterations",
                      max_iterations,
                      "Krylov iterations per Newton step; the Newton step "
                      "then goes on with the best direction found. "
                      "Dimensionless.",
                      Patterns::Integer(1, 100000));
    prm.add_parameter(
      "Preconditioner",
      preconditioner_text,
      "'none', or 'probed Jacobi': weighted Jacobi with the diagonal of the "
      "simplified Jacobian (eqs. 18-20 of Cummins & Brackbill) probed "
      "matrix-free with 2 3^dim coloured residual evaluations once per step; "
      "or 'AMG': the mass plus theta^2 dt^2 times the elastic stiffness of "
      "each grain with the frozen contact and wall constraints (which "
      "couple the grains that touch), assembled and inverted by one "
      "algebraic multigrid V-cycle (Trilinos ML), set up again after each "
      "change of the contact status of more than four slots; or 'sparse "
      "Cholesky': the same matrix, symmetrised, factorised exactly "
      "(CHOLMOD) at the same moments, on one MPI process only: dearer "
      "to set up than a V-cycle, but it leaves one to three Krylov "
      "iterations per Newton step; or 'automatic': probed Jacobi for the "
      "steps up to Automatic CFL number, the assembled matrix for longer "
      "ones (sparse Cholesky on one MPI process, AMG on more). "
      "Dimensionless.",
      Patterns::Selection("none|probed Jacobi|AMG|sparse Cholesky|automatic"));
    prm.add_parameter(
      "Automatic CFL number",
      automatic_cfl,
      "With Preconditioner = automatic: the CFL number c dt / h of a step "
      "(c the largest elastic wave speed at rest, h the smallest cell) up "
      "to which probed Jacobi preconditions it; longer steps take the "
      "assembled matrix, whose setup costs more than the Krylov iterations "
      "it saves at short steps. Dimensionless.",
      Patterns::Double(0.));
    prm.add_parameter("Jacobi weight",
                      jacobi_weight,
                      "omega of y = omega D^-1 r (irrelevant to GMRES with one "
                      "sweep). Dimensionless.",
                      Patterns::Double(0.01, 2.));
    prm.add_parameter("Jacobi sweeps",
                      jacobi_sweeps,
                      "Weighted Jacobi sweeps per preconditioner "
                      "application; each sweep after the first costs one "
                      "Jacobian-vector product. Dimensionless.",
                      Patterns::Integer(1, 20));
    prm.leave_subsection();
  }



  void
  LinearSolverParameters::check()
  {
    solver = parse_choice<KrylovSolver>("Linear solver/Solver = " + solver_text,
                                        solver_text,
                                        {{"GMRES", KrylovSolver::gmres},
                                         {"FGMRES", KrylovSolver::fgmres}});
    preconditioner = parse_choice<Preconditioner>(
      "Linear solver/Preconditioner = " + preconditioner_text,
      preconditioner_text,
      {{"none", Preconditioner::none},
       {"probed Jacobi", Preconditioner::probed_jacobi},
       {"AMG", Preconditioner::amg},
       {"sparse Cholesky", Preconditioner::sparse_cholesky},
       {"automatic", Preconditioner::automatic}});
    flexible = (solver == KrylovSolver::fgmres);
    if (jacobi_sweeps > 1 && !flexible &&
        (preconditioner == Preconditioner::probed_jacobi ||
         preconditioner == Preconditioner::automatic))
      throw InputError("Linear solver/Jacobi sweeps",
                       "more than one sweep makes the preconditioner change "
                       "from one application to the next (it contains "
                       "finite-difference products); set Linear solver/"
                       "Solver = FGMRES.");
  }
} // namespace grainmpm
