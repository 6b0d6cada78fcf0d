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



  // ---------------------------------------------------------- checkpoint

  void
  CheckpointParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    prm.add_parameter("Steps between checkpoints",
                      steps_between,
                      "Write a checkpoint every this many time steps; 0: "
                      "never (by steps). A checkpoint is the directory "
                      "checkpoint-NNNNNN (the step number) in the output "
                      "directory: the triangulation and the material points "
                      "with all properties (deal.II serialization), time, "
                      "time step, step number, the energy ledger and the "
                      "output records. It is written under a temporary "
                      "name and renamed when complete, so a run killed "
                      "while writing leaves the previous checkpoint usable. "
                      "Dimensionless.",
                      Patterns::Integer(0));
    prm.add_parameter("Minutes between checkpoints",
                      minutes_between,
                      "Write a checkpoint when this much wall-clock time has "
                      "passed since the last one (checked after every "
                      "step); 0: never (by time). Units: minutes.",
                      Patterns::Double(0.));
    prm.add_parameter("Checkpoints kept",
                      n_kept,
                      "How many of the newest checkpoints to keep; older "
                      "ones are deleted. Dimensionless.",
                      Patterns::Integer(1));
    prm.add_parameter("Resume from",
                      resume_from,
                      "A checkpoint directory (for example "
                      "results/checkpoint-000100) to continue from, with "
                      "the same parameter file otherwise; energy.csv and "
                      "grains.csv are cut back to the checkpoint and "
                      "continued. Empty: start at t = 0.");
    prm.add_parameter(
      "Replace other checkpoints",
      replace_other_checkpoints,
      "A fresh run (Resume from empty) that writes checkpoints refuses to "
      "start in an output directory that already holds checkpoints, which "
      "belong to another run: they would be replaced or deleted as old. "
      "true: start anyway; those checkpoints are kept, except one that "
      "this run's checkpoint of the same step replaces, and only this "
      "run's own checkpoints are deleted as old.",
      Patterns::Bool());
    prm.leave_subsection();
  }



  // ----------------------------------------------------- material points

  void
  MaterialPointParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    prm.add_parameter("Particles per cell",
                      particles_per_cell,
                      "Number of material points per cell and direction in "
                      "a regular arrangement (2 gives 4 per cell in 2D). "
                      "Dimensionless.",
                      Patterns::Integer(1, 10));
    prm.add_parameter(
      "Shape functions",
      shape_functions_text,
      "The weights with which a material point talks to the grid nodes. "
      "'linear': the bilinear (trilinear) hat functions of the grid at the "
      "point (classic MPM; 2^dim nodes per point); a point crossing a cell "
      "face makes its force jump, which injects grid-scale noise. 'uGIMP': "
      "the hats averaged over the point's box (half the point spacing on "
      "each side; Bardenhagen & Kober 2004): the weights are C1 in the "
      "point position, up to 3^dim nodes per point. 'cpGIMP': the same with "
      "a box whose half-width along axis d grows with the deformation, "
      "sqrt((F F^T)_dd) times the initial one, at most half a cell "
      "(Wallstedt & Guilkey 2008). Near a box face the point's box is cut at "
      "the face, which keeps the partition of unity. uGIMP is the default: "
      "one wall impact's energy loss then falls under refinement, with "
      "linear it grows (doc/validation.md).",
      Patterns::Selection("linear|uGIMP|cpGIMP"));
    prm.leave_subsection();
  }



  void
  MaterialPointParameters::check()
  {
    shape_functions =
      parse_choice<ShapeFunctions>("Material points/Shape functions = " +
                                     shape_functions_text,
                                   shape_functions_text,
                                   {{"linear", ShapeFunctions::linear},
                                    {"uGIMP", ShapeFunctions::ugimp},
                                    {"cpGIMP", ShapeFunctions::cpgimp}});
  }



  // ------------------------------------------------------------- contact

  void
  ContactParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.add_parameter(
      "Contact model",
      model_text,
      "How grains interact where they meet. 'none': all deformable grains "
      "share one grid velocity field, so touching grains stick (classic "
      "single-field MPM). 'frictionless': Bardenhagen-Brackbill-Sulsky "
      "contact, every grain has its own field; no interpenetration, free "
      "separation, no tangential force. 'Coulomb friction': the same with "
      "Coulomb friction (stick/slip) of coefficient 'Friction coefficient'. "
      "Dimensionless.",
      Patterns::Selection("none|frictionless|Coulomb friction"));
    prm.add_parameter("Friction coefficient",
                      friction_coefficient,
                      "Coulomb friction coefficient between grains, used by "
                      "the 'Coulomb friction' model. Dimensionless.",
                      Patterns::Double(0.));
    prm.add_parameter(
      "Gap check",
      gap_check,
      "Whether contact (between grains, with rigid grains and with the "
      "walls) acts only where the surfaces meet within the step. At each "
      "node the surface of every grain is located along the contact normal "
      "from the volume its material points give the node (sum_p V_p S_ip) "
      "against the node's support, as for a flat surface; a grain may then "
      "approach its partner by the gap between the surfaces in one step, "
      "and only the faster part of the approach is removed. 'false': every "
      "approach at a node where two grains have mass is removed (contact "
      "about one cell early, and grains rotating next to a surface are "
      "pushed off it).",
      Patterns::Bool());
    prm.leave_subsection();
  }



  void
  ContactParameters::check()
  {
    model =
      parse_choice<ContactModel>("Contact/Contact model = " + model_text,
                                 model_text,
                                 {{"none", ContactModel::none},
                                  {"frictionless", ContactModel::frictionless},
                                  {"Coulomb friction",
                                   ContactModel::coulomb_friction}});
  }



  // -------------------------------------------------------------- output

  void
  OutputParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.add_parameter("Output directory",
                      directory,
                      "Directory for all output (created if missing): "
                      "particles.pvd, grid.pvd, contacts.pvd, energy.csv, "
                      "grains.csv, walls.csv, contacts.csv, original.prm "
                      "and parameters.prm. Dimensionless.");
    prm.add_parameter("Output interval",
                      interval,
                      "Simulated time between two graphical outputs and "
                      "grain history rows. Zero writes every step. "
                      "Units: time.",
                      Patterns::Double(0.));
    prm.add_parameter("Write particles",
                      write_particles,
                      "Write particles.pvd and the particle .vtu files.");
    prm.add_parameter("Write grid",
                      write_grid,
                      "Write grid.pvd and the grid .vtu files.");
    prm.add_parameter("Write grain history",
                      write_grain_history,
                      "Write grains.csv (per grain centre of mass, velocity, "
                      "angular velocity, rotation, coordination number) at "
                      "every output.");
    prm.add_parameter("Write contacts",
                      write_contacts,
                      "Write contacts.csv (per pair of grains in contact: "
                      "the mean contact force over the output interval, its "
                      "normal and tangential parts, contact point, normal, "
                      "mobilised friction) and contacts.pvd with the "
                      "contacts/*.vtu force chains (a line between the "
                      "centres of two grains in contact, or from a grain's "
                      "centre to its contact point with a rigid grain) at "
                      "every output.");
    prm.add_parameter("Test mode",
                      test_mode,
                      "Print only what is deterministic (no timings, no "
                      "file names with paths) and a final summary, for the "
                      "regression tests.");
    prm.leave_subsection();
  }



  void
  OutputParameters::check() const
  {
    if (directory.empty())
      throw InputError("Output/Output directory", "must not be empty.");
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



  template struct BackgroundGridParameters<2>;
  template struct BackgroundGridParameters<3>;
  template struct PhysicsParameters<2>;
  template struct PhysicsParameters<3>;
  template struct Parameters<2>;
  template struct Parameters<3>;
} // namespace grainmpm
