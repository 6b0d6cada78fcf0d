// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_file.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/particles/grain_geometry.h>
#include <grainmpm/particles/grain_list.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    template <int dim>
    std::string
    point_to_string(const Point<dim> &point)
    {
      std::ostringstream out;
      out << '(';
      for (unsigned int d = 0; d < dim; ++d)
        out << (d > 0 ? ", " : "") << point[d];
      out << ')';
      return out.str();
    }
  } // namespace



  // ------------------------------------------------------------- physics

  template <int dim>
  void
  PhysicsParameters<dim>::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Physics");
    prm.add_parameter("Gravity",
                      gravity,
                      "The gravitational acceleration vector, one component "
                      "per direction. Units: length/time^2.");
    prm.add_parameter(
      "Two-dimensional model",
      two_dimensional_model_text,
      "The idealisation of a two-dimensional run: 'plane strain' (thick "
      "grains, the out-of-plane strain is zero) or 'plane stress' (thin "
      "disks such as photoelastic models). Ignored in 3D. Dimensionless.",
      Patterns::Selection("plane strain|plane stress"));
    prm.leave_subsection();
  }



  template <int dim>
  void
  PhysicsParameters<dim>::check()
  {
    two_dimensional_model = parse_choice<TwoDimensionalModel>(
      "Physics/Two-dimensional model = " + two_dimensional_model_text,
      two_dimensional_model_text,
      {{"plane strain", TwoDimensionalModel::plane_strain},
       {"plane stress", TwoDimensionalModel::plane_stress}});
  }



  // ------------------------------------------------------------ aggregate

  template <int dim>
  void
  Parameters<dim>::declare(ParameterHandler               &prm,
                           const std::vector<std::string> &material_names,
                           const std::vector<std::string> &grain_names)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "The space dimension of the run, 2 or 3. "
                      "Dimensionless.");
    grid.declare(prm);
    physics.declare(prm);

    materials.resize(material_names.size());
    prm.enter_subsection("Materials");
    for (unsigned int m = 0; m < material_names.size(); ++m)
      {
        materials[m].name = material_names[m];
        prm.enter_subsection(material_names[m]);
        materials[m].declare(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    grains.resize(grain_names.size());
    prm.enter_subsection("Grains");
    prm.add_parameter(
      "Grain list file",
      grain_list_file,
      "Optional CSV file with one grain per line (for large assemblies), in "
      "addition to the 'Grain N' subsections. Columns: shape, centre (" +
        std::to_string(dim) + " numbers), radius, size (" +
        std::to_string(dim) +
        " numbers), rotation in degrees, material name, velocity (" +
        std::to_string(dim) +
        " numbers). Lines starting with # are comments. Relative paths are "
        "relative to the working directory.");
    for (unsigned int g = 0; g < grain_names.size(); ++g)
      {
        grains[g].source = "Grains/" + grain_names[g];
        prm.enter_subsection(grain_names[g]);
        grains[g].declare(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    random_packing.declare(prm);

    material_points.declare(prm);
    contact.declare(prm);
    time_stepping.declare(prm);
    nonlinear_solver.declare(prm);
    linear_solver.declare(prm);
    output.declare(prm);
    checkpoint.declare(prm);
    load_balancing.declare(prm);
  }



  template <int dim>
  void
  Parameters<dim>::parse(const std::string &filename, ParameterHandler &prm)
  {
    auto material_names = find_subsections(filename, "Materials");
    auto grain_names    = find_subsections(filename, "Grains");
    declare(prm, material_names, grain_names);
    prm.parse_input(filename, "", false, true);
    check();
  }



  template <int dim>
  void
  Parameters<dim>::check()
  {
    grid.check();
    physics.check();
    material_points.check();
    contact.check();
    time_stepping.check();
    nonlinear_solver.check();
    linear_solver.check();
    output.check();
    for (auto &material : materials)
      material.check();

    // Grains from the list file come after the individually described ones
    // and before those of the random packing. They replace the ones of an
    // earlier call, so that check() can be repeated.
    const auto first_listed = grains.end() - n_packed_grains - n_listed_grains;
    grains.erase(first_listed, first_listed + n_listed_grains);
    n_listed_grains = 0;
    if (!grain_list_file.empty())
      {
        const auto listed = read_grain_list<dim>(grain_list_file);
        grains.insert(grains.end() - n_packed_grains,
                      listed.begin(),
                      listed.end());
        n_listed_grains = listed.size();
      }

    // The grains of the random packing are made by add_random_packing().
    if (random_packing.n_grains > 0)
      random_packing.check(grid);

    if (grains.empty() && random_packing.n_grains == 0)
      throw InputError("Grains",
                       "no grain is described: add a subsection 'Grain 1', "
                       "a Grain list file or a Random packing.");

    for (auto &grain : grains)
      check_grain(grain);
  }



  template <int dim>
  void
  Parameters<dim>::apply_mass_scaling()
  {
    if (masses_scaled)
      return;
    const double alpha = time_stepping.mass_scaling;
    for (auto &material : materials)
      material.density *= alpha;
    physics.gravity /= alpha;
    masses_scaled = true;
  }



  template <int dim>
  void
  Parameters<dim>::check_grain(GrainParameters<dim> &grain) const
  {
    grain.check(grain.source + "/");

    // The material must exist.
    bool found = false;
    for (unsigned int m = 0; m < materials.size(); ++m)
      if (materials[m].name == grain.material)
        {
          grain.material_index = m;
          found                = true;
        }
    if (!found)
      {
        std::string known;
        for (const auto &material : materials)
          known += (known.empty() ? "" : ", ") + material.name;
        throw InputError(grain.source + "/Material = " + grain.material,
                         "there is no material of this name in "
                         "subsection Materials (defined: " +
                           (known.empty() ? std::string("none") : known) +
                           ").");
      }

    // The grain must lie inside the background grid.
    const auto box = bounding_box(grain);
    for (unsigned int d = 0; d < dim; ++d)
      if (box.first[d] < grid.lower_corner[d] ||
          box.second[d] > grid.upper_corner[d])
        throw InputError(
          grain.source,
          "the grain (bounding box " + point_to_string(box.first) + " to " +
            point_to_string(box.second) +
            ") does not lie inside the background grid " +
            point_to_string(grid.lower_corner) + " to " +
            point_to_string(grid.upper_corner) +
            ": move it (Centre) or enlarge the grid (Background grid).");
  }



  template struct PhysicsParameters<2>;
  template struct PhysicsParameters<3>;
  template struct Parameters<2>;
  template struct Parameters<3>;
} // namespace grainmpm
