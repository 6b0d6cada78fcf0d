// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// random_packing() with Deposition = rolling (2D): each disk rolls over the
// disks it lands on until both sides hold it.
// - No two disks overlap (distance >= (r_i + r_j)(1 + gap)) and all lie in
//   the box.
// - Every disk rests on the floor, against a side of the box and on an
//   earlier disk, or on two earlier disks whose centres lie on either side
//   of its own (touching within round-off): nothing is held from one side
//   only, as a disk that stuck where it first landed may be.
// - The packing fraction of the filled part of the box is printed
//   (rounded) and is above that of sticking deposition with the same
//   parameters (0.65).
// - The same Seed gives the same packing.
// - In 3D the entry is refused, naming 'Random packing/Deposition'.

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/random_packing.h>

#include <deal.II/base/mpi.h>

#include <cmath>

#include "../tests.h"

using namespace grainmpm;

std::string
yes_no(const bool condition)
{
  return condition ? "yes" : "no";
}



double
packing_fraction(const std::vector<GrainParameters<2>> &grains,
                 const double                           width)
{
  double area = 0., top = 0.;
  for (const auto &grain : grains)
    {
      area += M_PI * grain.radius * grain.radius;
      top = std::max(top, grain.centre[1] + grain.radius);
    }
  return area / (top * width);
}



/**
 * Whether no two @p grains overlap and all lie in the box of width
 * @p width; returns the number of grains resting neither on the floor, nor
 * against a side and on an earlier grain, nor on earlier grains on both
 * sides of their centre.
 */
unsigned int
check(const std::vector<GrainParameters<2>> &grains,
      const double                           width,
      bool                                  &separate,
      bool                                  &inside)
{
  unsigned int one_sided = 0;
  for (unsigned int i = 0; i < grains.size(); ++i)
    {
      const auto  &a = grains[i];
      const double r = a.radius;
      inside         = inside && a.centre[0] - r >= -1e-12 &&
               a.centre[0] + r <= width + 1e-12 && a.centre[1] - r >= -1e-12;
      bool on_floor = std::abs(a.centre[1] - r) < 1e-9;
      bool on_side  = std::abs(a.centre[0] - r) < 1e-9 ||
                     std::abs(a.centre[0] + r - width) < 1e-9;
      bool left = false, right = false;
      for (unsigned int j = 0; j < grains.size(); ++j)
        if (j != i)
          {
            const double distance = a.centre.distance(grains[j].centre);
            const double contact  = (r + grains[j].radius) * 1.02;
            separate = separate && distance >= contact * (1. - 1e-12);
            if (j < i && std::abs(distance - contact) < 1e-9 * contact)
              {
                left  = left || grains[j].centre[0] < a.centre[0];
                right = right || grains[j].centre[0] > a.centre[0];
              }
          }
      if (!(on_floor || (on_side && (left || right)) || (left && right)))
        ++one_sided;
    }
  return one_sided;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const double               width = 20.;
  RandomPackingParameters<2> parameters;
  parameters.n_grains       = 500;
  parameters.minimum_radius = 0.4;
  parameters.maximum_radius = 0.6;
  parameters.gap            = 0.02;
  parameters.material       = "glass";
  parameters.seed           = 3;
  parameters.upper_corner   = Point<2>(width, 60.);
  const auto   stuck        = random_packing(parameters);
  const double sticking     = packing_fraction(stuck, width);
  parameters.deposition     = "rolling";
  const auto grains         = random_packing(parameters);
  deallog << "2D: " << grains.size() << " disks" << std::endl;

  bool               separate = true, inside = true;
  const unsigned int one_sided = check(grains, width, separate, inside);
  deallog << "  no overlaps (with the gap): " << yes_no(separate) << std::endl;
  deallog << "  inside the box: " << yes_no(inside) << std::endl;
  bool ignored_separate = true, ignored_inside = true;
  deallog << "  disks held from one side only: " << one_sided
          << " (sticking deposition: "
          << check(stuck, width, ignored_separate, ignored_inside) << ")"
          << std::endl;
  const double rolling = packing_fraction(grains, width);
  deallog << "  packing fraction of the filled box: "
          << std::round(100. * rolling) / 100.
          << ", sticking: " << std::round(100. * sticking) / 100.
          << ", denser: " << yes_no(rolling > sticking + 0.05) << std::endl;

  const auto again = random_packing(parameters);
  bool       same  = again.size() == grains.size();
  for (unsigned int i = 0; same && i < grains.size(); ++i)
    same = (again[i].centre == grains[i].centre);
  deallog << "  same seed, same packing: " << yes_no(same) << std::endl;

  RandomPackingParameters<3> spheres;
  spheres.n_grains       = 10;
  spheres.minimum_radius = 0.4;
  spheres.maximum_radius = 0.6;
  spheres.material       = "glass";
  spheres.deposition     = "rolling";
  spheres.upper_corner   = Point<3>(4., 4., 4.);
  BackgroundGridParameters<3> grid;
  grid.upper_corner = spheres.upper_corner;
  try
    {
      spheres.check(grid);
      deallog << "3D: rolling refused: no" << std::endl;
    }
  catch (const InputError &error)
    {
      deallog
        << "3D: rolling refused, naming the entry: "
        << yes_no(std::string(error.what()).find("Random packing/Deposition") !=
                  std::string::npos)
        << std::endl;
    }
}
