// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/particles/grain_parameters.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <cmath>

namespace grainmpm
{
  // -------------------------------------------------------------- grains

  template <int dim>
  GrainParameters<dim>::GrainParameters()
  {
    shape_text = (dim == 2 ? "disk" : "sphere");
    for (unsigned int d = 0; d < dim; ++d)
      {
        centre[d] = 0.5;
        size[d]   = 0.2;
        initial_velocity += std::string(d > 0 ? "; " : "") + "0";
      }
    prescribed_velocity = initial_velocity;
  }



  template <int dim>
  void
  GrainParameters<dim>::declare(ParameterHandler &prm)
  {
    prm.add_parameter("Shape",
                      shape_text,
                      "The shape of the grain: 'disk', 'rectangle' or "
                      "'polygon' in 2D, 'sphere' or 'box' in 3D. "
                      "Dimensionless.",
                      Patterns::Anything());
    prm.add_parameter("Centre",
                      centre,
                      "Centre of the disk, sphere, rectangle or box. "
                      "Units: length.");
    prm.add_parameter("Radius",
                      radius,
                      "Radius of a disk or sphere. Units: length.",
                      Patterns::Double(0.));
    prm.add_parameter("Size",
                      size,
                      "Edge lengths of a rectangle or box, one per "
                      "direction (before rotation). Units: length.");
    prm.add_parameter("Rotation",
                      rotation,
                      "Counter-clockwise rotation of a rectangle or box about "
                      "its centre (about the z axis in 3D). Units: degrees.");
    prm.add_parameter("Vertices",
                      vertices_text,
                      "Vertices of a polygon in counter-clockwise or "
                      "clockwise order, as 'x1, y1; x2, y2; ...'. "
                      "Units: length.");
    prm.add_parameter("Material",
                      material,
                      "Name of the material (a subsection of 'Materials') "
                      "the grain is made of. Dimensionless.");
    prm.add_parameter("Initial velocity",
                      initial_velocity,
                      "Initial velocity of the grain's material points, one "
                      "expression of the coordinates x, y (, z) per "
                      "component, separated by ';' (deal.II FunctionParser "
                      "syntax, e.g. '0.1; -0.2*x'). Units: length/time.");
    prm.add_parameter("Initial stress",
                      initial_stress,
                      initial_stress_syntax() +
                        "Empty: the material's Initial stress. Not for rigid "
                        "grains. Units: stress.");
    prm.add_parameter("Rigid",
                      rigid,
                      "If true, the grain is a rigid body that moves with the "
                      "prescribed velocity and acts on other grains through "
                      "contact as a body of infinite mass (platens, pistons, "
                      "impactors).");
    prm.add_parameter(
      "Prescribed velocity",
      prescribed_velocity,
      "Velocity of a rigid grain, one expression of x, y (, z) and the "
      "time t per component separated by ';'. Ignored unless Rigid is "
      "true. A velocity that does not vary in space translates the grain, "
      "and contact then uses its exact shape (normal and distance of the "
      "surface); one that varies in space (a rotation) falls back on the "
      "grain's material points from its first step. Units: length/time.");
  }



  template <int dim>
  void
  GrainParameters<dim>::check(const std::string &prefix)
  {
    const std::string entry = prefix + "Shape = " + shape_text;
    shape                   = parse_choice<GrainShape>(
      entry,
      shape_text,
      {{"disk", GrainShape::disk},
                         {"rectangle", GrainShape::rectangle},
                         {"polygon", GrainShape::polygon},
                         {"sphere", GrainShape::sphere},
                         {"box", GrainShape::box}},
      "unknown shape (use " +
        std::string(dim == 2 ? "disk, rectangle or polygon" : "sphere or box") +
        ").");

    const bool is_2d_shape =
      (shape == GrainShape::disk || shape == GrainShape::rectangle ||
       shape == GrainShape::polygon);
    if (is_2d_shape != (dim == 2))
      throw InputError(entry,
                       "this shape does not exist in " + std::to_string(dim) +
                         "D (use " +
                         std::string(dim == 2 ? "disk, rectangle or polygon" :
                                                "sphere or box") +
                         ").");

    for (unsigned int d = 0; d < dim; ++d)
      if (!std::isfinite(centre[d]))
        throw InputError(prefix + "Centre",
                         "coordinate " + std::to_string(d + 1) +
                           " is not a finite number.");
    if (!std::isfinite(rotation))
      throw InputError(prefix + "Rotation", "must be a finite number.");
    if ((shape == GrainShape::disk || shape == GrainShape::sphere) &&
        !(radius > 0. && std::isfinite(radius)))
      throw InputError(prefix + "Radius", "must be positive and finite.");
    if (shape == GrainShape::rectangle || shape == GrainShape::box)
      for (unsigned int d = 0; d < dim; ++d)
        if (!(size[d] > 0. && std::isfinite(size[d])))
          throw InputError(prefix + "Size",
                           "every edge length must be positive and finite.");

    vertices.clear();
    if (shape == GrainShape::polygon)
      {
        for (const auto &vertex :
             Utilities::split_string_list(vertices_text, ';'))
          {
            const auto coordinates = parse_numbers(vertex, prefix + "Vertices");
            if (coordinates.size() != dim)
              throw InputError(prefix + "Vertices = " + vertices_text,
                               "each vertex needs " + std::to_string(dim) +
                                 " coordinates separated by ','.");
            Point<dim> point;
            for (unsigned int d = 0; d < dim; ++d)
              point[d] = coordinates[d];
            vertices.push_back(point);
          }
        if (vertices.size() < 3)
          throw InputError(prefix + "Vertices = " + vertices_text,
                           "a polygon needs at least three vertices.");
        // A simple polygon: no two edges that do not share a vertex cross
        // (a bow tie has no inside and outside the generator can tell).
        const unsigned int n     = vertices.size();
        const auto         cross = [](const Point<dim> &a,
                              const Point<dim> &b,
                              const Point<dim> &c) {
          return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        };
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = i + 2; j < n; ++j)
            {
              if (i == 0 && j == n - 1)
                continue;
              const Point<dim> &p = vertices[i], &q = vertices[(i + 1) % n];
              const Point<dim> &r = vertices[j], &t = vertices[(j + 1) % n];
              if (cross(p, q, r) * cross(p, q, t) < 0. &&
                  cross(r, t, p) * cross(r, t, q) < 0.)
                throw InputError(prefix + "Vertices = " + vertices_text,
                                 "the edges from vertex " +
                                   std::to_string(i + 1) + " and from vertex " +
                                   std::to_string(j + 1) +
                                   " cross: the polygon intersects itself. "
                                   "List the vertices in order around it.");
            }
        double area = 0.;
        for (unsigned int i = 0; i < n; ++i)
          area += cross(Point<dim>(), vertices[i], vertices[(i + 1) % n]);
        if (!(std::abs(area) > 0.))
          throw InputError(prefix + "Vertices = " + vertices_text,
                           "the polygon has no area.");
      }

    if (Utilities::split_string_list(initial_velocity, ';').size() != dim)
      throw InputError(prefix + "Initial velocity = " + initial_velocity,
                       "needs " + std::to_string(dim) +
                         " expressions separated by ';'.");
    if (rigid &&
        Utilities::split_string_list(prescribed_velocity, ';').size() != dim)
      throw InputError(prefix + "Prescribed velocity = " + prescribed_velocity,
                       "needs " + std::to_string(dim) +
                         " expressions separated by ';'.");
  }



  // ------------------------------------------------------ random packing

  template <int dim>
  void
  RandomPackingParameters<dim>::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Random packing");
    prm.add_parameter(
      "Number of grains",
      n_grains,
      "Number of disks (2D) or spheres (3D) to generate by ballistic "
      "deposition into the box between Lower corner and Upper corner "
      "(dropped along -y at random lateral positions, each placed where it "
      "comes to rest lowest among Drop attempts tries, touching the floor "
      "or a grain), in addition to the described "
      "grains. 0: none. The run writes them to packing.csv in the output "
      "directory, a grain list file for 'Grains/Grain list file'. "
      "Dimensionless.",
      Patterns::Integer(0));
    prm.add_parameter("Minimum radius",
                      minimum_radius,
                      "Smallest grain radius; radii are uniform between "
                      "the minimum and the maximum. Units: length.",
                      Patterns::Double(0.));
    prm.add_parameter("Maximum radius",
                      maximum_radius,
                      "Largest grain radius. Units: length.",
                      Patterns::Double(0.));
    prm.add_parameter("Gap",
                      gap,
                      "Clearance between deposited grains as a fraction of "
                      "the sum of their radii, so that no two grains share "
                      "a material point at the start. Dimensionless.",
                      Patterns::Double(0., 1.));
    prm.add_parameter("Lower corner",
                      lower_corner,
                      "Corner of the deposition box with the smallest "
                      "coordinates; its y coordinate is the floor. Units: "
                      "length.");
    prm.add_parameter("Upper corner",
                      upper_corner,
                      "Corner of the deposition box with the largest "
                      "coordinates. Units: length.");
    prm.add_parameter("Material",
                      material,
                      "Name of the material (a subsection of Materials) of "
                      "the generated grains.");
    prm.add_parameter("Drop attempts",
                      n_candidates,
                      "Each grain is dropped at this many random lateral "
                      "positions and placed where it comes to rest lowest; "
                      "more attempts fill holes and give denser packings "
                      "(1: plain ballistic deposition). Dimensionless.",
                      Patterns::Integer(1));
    prm.add_parameter("Seed",
                      seed,
                      "Seed of the random numbers (std::mt19937): the same "
                      "seed gives the same packing. Dimensionless.",
                      Patterns::Integer(0));
    prm.add_parameter(
      "Deposition",
      deposition,
      "How a dropped grain comes to rest. 'sticking': where it first "
      "touches the floor or a grain (most grains then rest on one grain; "
      "packing fraction 0.65 for 500 disks). 'rolling' (2D only): it then "
      "rolls down over the grains it lands on until it rests on the floor, "
      "against a side of the box, or on two grains on either side of its "
      "centre, so that every grain is held from both sides (packing "
      "fraction 0.75 for the same 500 disks).",
      Patterns::Selection("sticking|rolling"));
    prm.leave_subsection();
  }



  template <int dim>
  void
  RandomPackingParameters<dim>::check(
    const BackgroundGridParameters<dim> &grid) const
  {
    if (!(maximum_radius >= minimum_radius) || !(minimum_radius > 0.))
      throw InputError("Random packing/Maximum radius",
                       "the radii must satisfy 0 < Minimum radius <= "
                       "Maximum radius.");
    for (unsigned int d = 0; d < dim; ++d)
      {
        if (!(upper_corner[d] - lower_corner[d] > 2. * maximum_radius))
          throw InputError("Random packing/Upper corner",
                           "the box must be wider than the largest grain "
                           "in every direction.");
        if (lower_corner[d] < grid.lower_corner[d] ||
            upper_corner[d] > grid.upper_corner[d])
          throw InputError("Random packing/Lower corner",
                           "the deposition box must lie inside the "
                           "background grid.");
      }
    if (material.empty())
      throw InputError("Random packing/Material",
                       "name the material of the generated grains.");
    if (deposition == "rolling" && dim != 2)
      throw InputError("Random packing/Deposition = rolling",
                       "rolling deposition is implemented in 2D only; use "
                       "'sticking' in 3D.");
  }



  template struct GrainParameters<2>;
  template struct GrainParameters<3>;
  template struct RandomPackingParameters<2>;
  template struct RandomPackingParameters<3>;
} // namespace grainmpm
