// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Parameters::parse() reads the described grains and the grain list file
// but generates no grains; add_random_packing() appends those of subsection
// Random packing. Calling check() or add_random_packing() again gives the
// same grains in the same order (nothing appended twice), in either order.

#include <grainmpm/base/parameters.h>
#include <grainmpm/particles/random_packing.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <fstream>
#include <sstream>

#include "../tests.h"

using namespace grainmpm;

// Source, centre, radius and material index of every grain.
template <int dim>
std::string
describe(const Parameters<dim> &parameters)
{
  std::ostringstream out;
  out << parameters.grains.size() << " grains (" << parameters.n_listed_grains
      << " listed, " << parameters.n_packed_grains << " packed)";
  return out.str();
}



template <int dim>
bool
same_grains(const Parameters<dim> &a, const Parameters<dim> &b)
{
  if (a.grains.size() != b.grains.size() ||
      a.n_listed_grains != b.n_listed_grains ||
      a.n_packed_grains != b.n_packed_grains)
    return false;
  for (unsigned int g = 0; g < a.grains.size(); ++g)
    if (a.grains[g].source != b.grains[g].source ||
        a.grains[g].centre != b.grains[g].centre ||
        a.grains[g].radius != b.grains[g].radius ||
        a.grains[g].shape != b.grains[g].shape ||
        a.grains[g].material_index != b.grains[g].material_index)
      return false;
  return true;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  {
    std::ofstream list("grains_02.csv");
    list << "# shape, centre, radius, size, rotation, material, velocity\n"
         << "disk, 1, 3, 0.3, 0, 0, 0, sand, 0, 0\n"
         << "rectangle, 3, 3, 0, 0.5, 0.4, 30, rock, 0, -1\n";
  }
  {
    std::ofstream file("random_packing_02.prm");
    file << "set Dimension = 2\n"
         << "subsection Background grid\n"
         << "  set Upper corner = 4, 4\n"
         << "  set Number of cells = 16, 16\n"
         << "end\n"
         << "subsection Materials\n"
         << "  subsection sand\n  end\n"
         << "  subsection rock\n  end\n"
         << "end\n"
         << "subsection Grains\n"
         << "  set Grain list file = grains_02.csv\n"
         << "  subsection Grain 1\n"
         << "    set Centre = 2, 3.5\n"
         << "    set Radius = 0.3\n"
         << "    set Material = rock\n"
         << "  end\n"
         << "end\n"
         << "subsection Random packing\n"
         << "  set Number of grains = 6\n"
         << "  set Minimum radius = 0.2\n"
         << "  set Maximum radius = 0.3\n"
         << "  set Upper corner = 4, 2\n"
         << "  set Material = sand\n"
         << "end\n";
  }

  ParameterHandler prm;
  Parameters<2>    parameters;
  parameters.parse("random_packing_02.prm", prm);
  deallog << "parsed: " << describe(parameters) << std::endl;
  const Parameters<2> parsed = parameters;

  parameters.check();
  deallog << "checked again: " << describe(parameters) << ", the same grains: "
          << (same_grains(parameters, parsed) ? "yes" : "no") << std::endl;

  add_random_packing(parameters);
  deallog << "packed: " << describe(parameters) << std::endl;
  for (const auto &grain : parameters.grains)
    deallog << "  " << grain.source << ", material "
            << parameters.materials[grain.material_index].name << std::endl;
  const Parameters<2> packed = parameters;

  add_random_packing(parameters);
  deallog << "packed again: " << describe(parameters) << ", the same grains: "
          << (same_grains(parameters, packed) ? "yes" : "no") << std::endl;

  parameters.check();
  deallog << "checked after packing: " << describe(parameters)
          << ", the same grains: "
          << (same_grains(parameters, packed) ? "yes" : "no") << std::endl;

  parameters.random_packing.n_grains = 0;
  add_random_packing(parameters);
  deallog << "packing switched off: " << describe(parameters)
          << ", the grains of the parameter file: "
          << (same_grains(parameters, parsed) ? "yes" : "no") << std::endl;
}
