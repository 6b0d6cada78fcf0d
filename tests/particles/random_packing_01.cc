// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// random_packing(): ballistic deposition of polydisperse disks (2D) and
// spheres (3D) into a box.
// - No two grains overlap (distance >= (r_i + r_j)(1 + gap)), all lie in
//   the box, and every grain rests on the floor or on a grain (it touches
//   one within round-off): the packing is deposited, not sprinkled.
// - The radii span the requested range; the packing fraction of the filled
//   part of the box is printed (rounded).
// - The same Seed gives the same packing, another Seed another one.
// - write_grain_list() then 'Grains/Grain list file' reads the same grains
//   back (through a whole parameter file).
// - A box too small for the grains stops with a message naming
//   'Random packing/Upper corner'.

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/grain_list.h>
#include <grainmpm/particles/random_packing.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <fstream>

#include "../tests.h"

using namespace grainmpm;

std::string
yes_no(const bool condition)
{
  return condition ? "yes" : "no";
}



template <int dim>
void
test(const unsigned int n, const double width)
{
  RandomPackingParameters<dim> parameters;
  parameters.n_grains       = n;
  parameters.minimum_radius = 0.4;
  parameters.maximum_radius = 0.6;
  parameters.gap            = 0.02;
  parameters.material       = "glass";
  parameters.seed           = 3;
  parameters.n_candidates   = (dim == 2 ? 20 : 100);
  for (unsigned int d = 0; d < dim; ++d)
    parameters.upper_corner[d] = width;
  parameters.upper_corner[1] = 60.;

  const auto grains = random_packing(parameters);
  deallog << dim << "D: " << grains.size() << " grains" << std::endl;

  bool   separate = true, inside = true, supported = true;
  double r_min = 1e300, r_max = 0., volume = 0., top = 0.;
  for (unsigned int i = 0; i < grains.size(); ++i)
    {
      const auto  &a = grains[i];
      const double r = a.radius;
      r_min          = std::min(r_min, r);
      r_max          = std::max(r_max, r);
      volume += (dim == 2 ? M_PI * r * r : 4. / 3. * M_PI * r * r * r);
      top = std::max(top, a.centre[1] + r);
      for (unsigned int d = 0; d < dim; ++d)
        inside = inside && a.centre[d] - r >= -1e-12 &&
                 a.centre[d] + r <= parameters.upper_corner[d] + 1e-12;
      bool touches = std::abs(a.centre[1] - r) < 1e-9;
      for (unsigned int j = 0; j < grains.size(); ++j)
        if (j != i)
          {
            const double distance = a.centre.distance(grains[j].centre);
            const double contact  = (r + grains[j].radius) * 1.02;
            separate = separate && distance >= contact * (1. - 1e-12);
            if (j < i && std::abs(distance - contact) < 1e-9 * contact &&
                grains[j].centre[1] < a.centre[1])
              touches = true;
          }
      supported = supported && touches;
    }
  deallog << "  no overlaps (with the gap): " << yes_no(separate) << std::endl;
  deallog << "  inside the box: " << yes_no(inside) << std::endl;
  deallog << "  every grain rests on the floor or on an earlier grain: "
          << yes_no(supported) << std::endl;
  deallog << "  radii in [0.4, 0.6], spanning more than 90 % of it: "
          << yes_no(r_min >= 0.4 && r_max <= 0.6 && r_max - r_min > 0.18)
          << std::endl;
  double filled = top;
  for (unsigned int d = 0; d < dim; ++d)
    if (d != 1)
      filled *= parameters.upper_corner[d];
  deallog << "  packing fraction of the filled box: "
          << std::round(100. * volume / filled) / 100. << std::endl;

  const auto again = random_packing(parameters);
  bool       same  = again.size() == grains.size();
  for (unsigned int i = 0; same && i < grains.size(); ++i)
    same = (again[i].centre == grains[i].centre) &&
           (again[i].radius == grains[i].radius);
  parameters.seed  = 4;
  const auto other = random_packing(parameters);
  deallog << "  same seed, same packing: " << yes_no(same)
          << "; another seed, another: "
          << yes_no(other[0].centre != grains[0].centre) << std::endl;

  // Write, and read back through a whole parameter file.
  const std::string list = "packing_" + std::to_string(dim) + "d.csv";
  {
    std::ofstream out(list);
    write_grain_list<dim>(out, grains);
  }
  const std::string file = "read_" + std::to_string(dim) + "d.prm";
  {
    std::ofstream prm_file(file);
    prm_file << "set Dimension = " << dim << "\n"
             << "subsection Background grid\n  set Lower corner = "
             << (dim == 2 ? "0, 0" : "0, 0, 0")
             << "\n  set Upper corner = " << width << ", 60"
             << (dim == 3 ? ", " + std::to_string(width) : "")
             << "\n  set Number of cells = "
             << (dim == 2 ? "20, 40" : "8, 30, 8") << "\nend\n"
             << "subsection Materials\n  subsection glass\n  end\nend\n"
             << "subsection Grains\n  set Grain list file = " << list
             << "\nend\n";
  }
  ParameterHandler prm;
  Parameters<dim>  read;
  read.parse(file, prm);
  bool read_back = read.grains.size() == grains.size();
  for (unsigned int i = 0; read_back && i < grains.size(); ++i)
    read_back = read.grains[i].centre.distance(grains[i].centre) < 1e-10 &&
                std::abs(read.grains[i].radius - grains[i].radius) < 1e-10 &&
                read.grains[i].material == "glass";
  deallog << "  written and read back as a grain list file: "
          << yes_no(read_back) << std::endl;

  // Too many grains for the box.
  parameters.n_grains        = 10 * n;
  parameters.upper_corner[1] = 10.;
  try
    {
      random_packing(parameters);
      deallog << "  a full box is refused: no" << std::endl;
    }
  catch (const InputError &error)
    {
      deallog << "  a full box is refused, naming the entry: "
              << yes_no(std::string(error.what())
                          .find("Random packing/Upper corner") !=
                        std::string::npos)
              << std::endl;
    }
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>(500, 20.);
  test<3>(600, 8.);
}
