// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/grid/grid_parameters.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

namespace grainmpm
{
  // ---------------------------------------------------------------- grid

  template <int dim>
  BackgroundGridParameters<dim>::BackgroundGridParameters()
    : n_cells(dim, 20)
  {
    for (unsigned int d = 0; d < dim; ++d)
      upper_corner[d] = 1.;
    for (unsigned int f = 0; f < 2 * dim; ++f)
      boundary_conditions_text +=
        (f > 0 ? ", " : "") + std::string(face_name(f)) + ": free slip";
  }



  template <int dim>
  void
  BackgroundGridParameters<dim>::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Background grid");
    prm.add_parameter("Lower corner",
                      lower_corner,
                      "The corner of the box-shaped background grid with the "
                      "smallest coordinates, one number per direction. "
                      "Units: length.");
    prm.add_parameter("Upper corner",
                      upper_corner,
                      "The corner of the box-shaped background grid with the "
                      "largest coordinates. Units: length.");
    prm.add_parameter("Number of cells",
                      n_cells,
                      "Number of Q1 cells in each direction, one integer per "
                      "direction. Cells should be square (cubes): the time "
                      "step and the contact normals use the smallest cell "
                      "size. The grid is a coarse mesh, which p4est keeps on "
                      "every MPI rank, refined globally: for large parallel "
                      "runs choose numbers that share a factor 2^k (for "
                      "example 704, 592 = 176, 148 times 2^2), so that the "
                      "coarse mesh has at most 65536 cells. Dimensionless.",
                      Patterns::List(Patterns::Integer(1, 1 << 16), dim, dim));
    prm.add_parameter(
      "Boundary conditions",
      boundary_conditions_text,
      "What each face of the box does, as a comma-separated list of "
      "'face: type' with face one of x-, x+, y-, y+ (z-, z+ in 3D) and type "
      "one of 'free slip' (rigid frictionless wall that material can leave), "
      "'no slip' (grid velocity zero at the face), 'friction MU' (rigid wall "
      "with Coulomb friction coefficient MU) or 'open' (particles that leave "
      "are removed and counted). Faces not listed are free slip. "
      "Dimensionless.");
    prm.leave_subsection();
  }



  template <int dim>
  void
  BackgroundGridParameters<dim>::check()
  {
    const std::string entry = "Background grid/";
    for (unsigned int d = 0; d < dim; ++d)
      if (!(upper_corner[d] > lower_corner[d]))
        throw InputError(entry + "Upper corner",
                         "must be larger than the Lower corner in every "
                         "direction, but in direction " +
                           std::to_string(d) + " it is " +
                           std::to_string(upper_corner[d]) +
                           " <= " + std::to_string(lower_corner[d]) + ".");

    for (auto &condition : boundary_conditions)
      condition = BoundaryCondition();
    const std::string bc_entry =
      entry + "Boundary conditions = " + boundary_conditions_text;
    for (const auto &item :
         Utilities::split_string_list(boundary_conditions_text, ','))
      {
        const auto parts = Utilities::split_string_list(item, ':');
        if (parts.size() != 2)
          throw InputError(bc_entry,
                           "each item must read 'face: type', but '" + item +
                             "' does not.");
        std::vector<std::pair<std::string, unsigned int>> faces;
        for (unsigned int f = 0; f < 2 * dim; ++f)
          faces.emplace_back(face_name(f), f);
        const unsigned int face = parse_choice<unsigned int>(
          bc_entry,
          parts[0],
          faces,
          "unknown face '" + parts[0] + "' (use " +
            (dim == 2 ? "x-, x+, y-, y+" : "x-, x+, y-, y+, z-, z+") + ").");
        const auto         words = Utilities::split_string_list(parts[1], ' ');
        BoundaryCondition &condition = boundary_conditions[face];
        if (words.size() == 2 && words[0] == "friction")
          {
            condition.type = BoundaryType::friction;
            condition.friction_coefficient =
              parse_numbers(words[1], bc_entry)[0];
            if (condition.friction_coefficient < 0.)
              throw InputError(bc_entry,
                               "the friction coefficient of face " + parts[0] +
                                 " must not be negative.");
          }
        else
          condition.type = parse_choice<BoundaryType>(
            bc_entry,
            parts[1],
            {{"free slip", BoundaryType::free_slip},
             {"no slip", BoundaryType::no_slip},
             {"open", BoundaryType::open}},
            "unknown boundary type '" + parts[1] + "' for face " + parts[0] +
              " (use free slip, no slip, friction MU, open).");
      }
  }



  // ------------------------------------------------------ load balancing

  void
  LoadBalancingParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Load balancing");
    prm.add_parameter("Steps between repartitioning",
                      steps_between,
                      "With more than one MPI rank: repartition the cells "
                      "among the ranks at the start and every this many "
                      "time steps, so that each rank carries about the same "
                      "weight (material points follow their cells). 0: "
                      "never; the cells then stay where p4est put them, "
                      "equal numbers of cells per rank. Dimensionless.",
                      Patterns::Integer(0));
    prm.add_parameter("Particle weight",
                      particle_weight,
                      "The weight of a material point relative to a cell "
                      "in the repartitioning: a cell weighs 1 plus this "
                      "times its number of points (as in ASPECT and "
                      "step-68). Dimensionless.",
                      Patterns::Integer(0));
    prm.leave_subsection();
  }



  template struct BackgroundGridParameters<2>;
  template struct BackgroundGridParameters<3>;
} // namespace grainmpm
