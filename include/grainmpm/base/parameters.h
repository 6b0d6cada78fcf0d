// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_parameters_h
#define grainmpm_base_parameters_h

#include <grainmpm/base/config.h>
#include <grainmpm/materials/material_parameters.h>
#include <grainmpm/particles/grain_parameters.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * What a face of the background box does to material that reaches it.
   */
  enum class BoundaryType
  {
    free_slip, ///< unilateral, frictionless rigid wall
    no_slip,   ///< the grid velocity is set to zero
    friction,  ///< unilateral rigid wall with Coulomb friction
    open       ///< nothing; particles that leave are removed and counted
  };

  /**
   * The condition on one face of the box.
   */
  struct BoundaryCondition
  {
    BoundaryType type                 = BoundaryType::free_slip;
    double       friction_coefficient = 0.;
  };

  /** The name of box face @p face in the input: x-, x+, y-, y+, z-, z+. */
  inline const char *
  face_name(const unsigned int face)
  {
    static const char *const names[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
    return names[face];
  }

  /**
   * Subsection "Background grid": a box of Q1 cells.
   */
  template <int dim>
  struct BackgroundGridParameters
  {
    Point<dim>                lower_corner;
    Point<dim>                upper_corner;
    std::vector<unsigned int> n_cells;
    std::string               boundary_conditions_text;

    /** Parsed from boundary_conditions_text: faces x-, x+, y-, y+, z-, z+. */
    std::array<BoundaryCondition, 2 * dim> boundary_conditions;

    BackgroundGridParameters();
    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * The two-dimensional idealisation.
   */
  enum class TwoDimensionalModel
  {
    plane_strain,
    plane_stress
  };

  /**
   * Subsection "Physics".
   */
  template <int dim>
  struct PhysicsParameters
  {
    Tensor<1, dim>      gravity;
    std::string         two_dimensional_model_text = "plane strain";
    TwoDimensionalModel two_dimensional_model =
      TwoDimensionalModel::plane_strain;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * How grains interact where they meet (subsection "Contact").
   */
  enum class ContactModel
  {
    none,
    frictionless,
    coulomb_friction
  };

  /**
   * The shape functions of the particle-grid transfer (subsection
   * "Material points").
   */
  enum class ShapeFunctions
  {
    /** The Q1 hats S_i(x_p) of the grid (classic MPM). */
    linear,
    /**
     * Q1 hats averaged over a fixed box around each point (uGIMP,
     * Bardenhagen & Kober 2004).
     */
    ugimp,
    /**
     * Q1 hats averaged over a box that stretches with the deformation
     * (cpGIMP, Wallstedt & Guilkey 2008).
     */
    cpgimp
  };

  /**
   * Subsection "Material points".
   */
  struct MaterialPointParameters
  {
    unsigned int   particles_per_cell   = 2;
    std::string    shape_functions_text = "uGIMP";
    ShapeFunctions shape_functions      = ShapeFunctions::ugimp;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * Subsection "Contact".
   */
  struct ContactParameters
  {
    std::string  model_text           = "frictionless";
    ContactModel model                = ContactModel::frictionless;
    double       friction_coefficient = 0.;
    bool         gap_check            = false;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * Order of the explicit stress update.
   */
  enum class StressUpdate
  {
    usf,
    musl,
    usl
  };

  /**
   * The time integration schemes (subsection "Time stepping").
   */
  enum class TimeSteppingScheme
  {
    explicit_leapfrog,
    implicit_theta
  };

  /**
   * How the particles get their new velocity from the grid.
   */
  enum class VelocityUpdate
  {
    flip,
    pic,
    blend
  };

  /**
   * The grid mass matrix of the implicit scheme (see MassMatrix).
   */
  enum class MassMatrixType
  {
    lumped,
    blended
  };

  /**
   * Subsection "Time stepping".
   */
  struct TimeSteppingParameters
  {
    std::string        scheme_text = "explicit leapfrog";
    TimeSteppingScheme scheme      = TimeSteppingScheme::explicit_leapfrog;
    /** Centring parameter of the implicit scheme, in [1/2, 1]. */
    double theta = 0.5;
    /** Smallest step the implicit failure policy may cut to (0: auto). */
    double minimum_time_step = 0.;
    /** Cut dt on a failed implicit step and grow it back afterwards. */
    bool adaptive_time_stepping = true;
    /** Consecutive easy steps before dt is doubled back. */
    unsigned int   steps_before_growth  = 2;
    std::string    stress_update_text   = "USF";
    StressUpdate   stress_update        = StressUpdate::usf;
    double         end_time             = 1.;
    double         time_step            = 0.;
    double         cfl_number           = 0.25;
    std::string    velocity_update_text = "FLIP";
    VelocityUpdate velocity_update      = VelocityUpdate::flip;
    /** The FLIP weight: set by check() to 1 (FLIP) or 0 (PIC). */
    double         flip_fraction           = 1.;
    unsigned int   maximum_number_of_steps = 100000000;
    std::string    mass_matrix_text        = "automatic";
    MassMatrixType mass_matrix             = MassMatrixType::lumped;
    /**
     * The consistent fraction alpha of the blended mass matrix: set by
     * check() to 0 with the lumped mass.
     */
    double consistent_mass_fraction = 0.95;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

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
    unsigned int  max_iterations      = 20;
    std::string   forcing_text        = "Eisenstat-Walker";
    ForcingTerm   forcing             = ForcingTerm::eisenstat_walker;
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
    unsigned int     max_status_changes   = 2;
    /** Hysteresis band of the contact status, in units of U. */
    double status_tolerance = 0.;
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
    amg
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
    std::string    preconditioner_text = "probed Jacobi";
    Preconditioner preconditioner      = Preconditioner::probed_jacobi;
    /** Set by check(): preconditioner is probed Jacobi. */
    bool         probed_jacobi = true;
    double       jacobi_weight = 1.;
    unsigned int jacobi_sweeps = 1;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };

  /**
   * Subsection "Output".
   */
  struct OutputParameters
  {
    std::string directory           = "results";
    double      interval            = 0.1;
    bool        write_particles     = true;
    bool        write_grid          = true;
    bool        write_grain_history = true;
    bool        write_contacts      = true;
    bool        test_mode           = false;

    void
    declare(ParameterHandler &prm);
    void
    check() const;
  };

  /**
   * Subsection "Checkpoint".
   */
  struct CheckpointParameters
  {
    unsigned int steps_between   = 0;
    double       minutes_between = 0.;
    unsigned int n_kept          = 2;
    std::string  resume_from;
    bool         replace_other_checkpoints = false;

    void
    declare(ParameterHandler &prm);
  };

  /**
   * Subsection "Load balancing": repartitioning of the cells among the MPI
   * ranks by their material points.
   */
  struct LoadBalancingParameters
  {
    unsigned int steps_between   = 100;
    unsigned int particle_weight = 10;

    void
    declare(ParameterHandler &prm);
  };

  template <int dim>
  struct Parameters
  {
    BackgroundGridParameters<dim>   grid;
    PhysicsParameters<dim>          physics;
    std::vector<MaterialParameters> materials;
    std::string                     grain_list_file;
    /**
     * The grains: the "Grain N" subsections, then the lines of the grain
     * list file (read by check()), then the grains of the random packing
     * (made by add_random_packing()).
     */
    std::vector<GrainParameters<dim>> grains;
    RandomPackingParameters<dim>      random_packing;
    /** How many of the grains come from the grain list file. */
    unsigned int n_listed_grains = 0;
    /** How many of the grains (the last ones) the random packing made. */
    unsigned int              n_packed_grains = 0;
    MaterialPointParameters   material_points;
    ContactParameters         contact;
    TimeSteppingParameters    time_stepping;
    NonlinearSolverParameters nonlinear_solver;
    LinearSolverParameters    linear_solver;
    OutputParameters          output;
    CheckpointParameters      checkpoint;
    LoadBalancingParameters   load_balancing;

    /**
     * Declare every entry. @p material_names and @p grain_names are the
     * subsections found in the file (see find_subsections()).
     */
    void
    declare(ParameterHandler               &prm,
            const std::vector<std::string> &material_names,
            const std::vector<std::string> &grain_names);

    /**
     * Declare, parse @p filename and check. Throws InputError or the
     * deal.II exception of a pattern mismatch (which names the entry).
     * Generates no grains: see add_random_packing().
     */
    void
    parse(const std::string &filename, ParameterHandler &prm);

    /**
     * Check every subsection and the checks that involve several entries:
     * read the grain list file, check each grain (check_grain()). Can be
     * called again with the same result: the grains of the list file
     * replace those of an earlier call.
     */
    void
    check();

    /**
     * Check @p grain (GrainParameters::check()) and what involves the other
     * subsections: its material exists (this sets its material index) and
     * it lies inside the background grid.
     */
    void
    check_grain(GrainParameters<dim> &grain) const;
  };
} // namespace grainmpm

#endif
