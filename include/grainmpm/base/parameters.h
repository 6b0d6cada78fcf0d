// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_parameters_h
#define grainmpm_base_parameters_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_parameters.h>
#include <grainmpm/grid/grid_parameters.h>
#include <grainmpm/materials/material_parameters.h>
#include <grainmpm/particles/grain_parameters.h>
#include <grainmpm/postprocess/output_parameters.h>
#include <grainmpm/solvers/solver_parameters.h>
#include <grainmpm/time_integration/time_stepping_parameters.h>
#include <grainmpm/transfer/material_point_parameters.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace grainmpm
{
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
     * Mass scaling (`Time stepping/Mass scaling` alpha): multiply the
     * density of every material by alpha and divide gravity by it, so that
     * inertia is alpha times the physical one while weights stay true.
     * Called once, by run(), after the grains are complete; a second call
     * changes nothing.
     */
    void
    apply_mass_scaling();

    /** Whether apply_mass_scaling() has scaled the densities. */
    bool masses_scaled = false;

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
