// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_grid_grid_parameters_h
#define grainmpm_grid_grid_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

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
} // namespace grainmpm

#endif
