// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Parameter errors: a missing material, a grain outside the grid, a
// negative density, an unknown shape, a bad boundary condition and two
// overlapping grains are rejected with a message that names the entry; a
// correct input passes.

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/material_point_layout.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <sstream>

#include "../tests.h"

using namespace grainmpm;

// A correct two-grain input; each case replaces one line.
const std::string correct_input = R"(
set Dimension = 2
subsection Background grid
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Number of cells = 10, 10
  set Boundary conditions = x-: free slip, x+: friction 0.2, y-: no slip, y+: open
end
subsection Materials
  subsection mat
    set Density = 2
  end
end
subsection Grains
  subsection Grain 1
    set Shape = disk
    set Centre = 0.3, 0.5
    set Radius = 0.2
    set Material = mat
  end
  subsection Grain 2
    set Shape = rectangle
    set Centre = 0.75, 0.5
    set Size = 0.2, 0.3
    set Material = mat
  end
end
)";

std::string
replace(const std::string &from, const std::string &to)
{
  std::string text     = correct_input;
  const auto  position = text.find(from);
  AssertThrow(position != std::string::npos, ExcMessage(from));
  return text.replace(position, from.size(), to);
}



void
check(const std::string &name,
      const std::string &input,
      const std::string &entry,
      const bool         generate = false)
{
  std::string message;
  try
    {
      ParameterHandler prm;
      Parameters<2>    parameters;
      parameters.declare(prm, {"mat"}, {"Grain 1", "Grain 2"});
      prm.parse_input_from_string(input);
      parameters.check();
      if (generate)
        {
          BackgroundGrid<2>             grid(parameters.grid, MPI_COMM_WORLD);
          Particles::ParticleHandler<2> particle_handler(
            grid.get_triangulation(),
            grid.get_mapping(),
            MaterialPointLayout<2>::n_properties);
          GrainGenerator<2>(parameters).generate(grid, particle_handler);
        }
      message = "ok";
    }
  catch (const InputError &error)
    {
      message = std::string("InputError: ") + error.what();
    }
  catch (const ExceptionBase &exception)
    {
      // Only the explanation, without the lines naming source files.
      std::ostringstream info;
      exception.print_info(info);
      std::istringstream lines(info.str());
      std::string        line;
      message = "deal.II exception:";
      while (std::getline(lines, line))
        if (line.find(".cc") == std::string::npos &&
            line.find(".h:") == std::string::npos && !line.empty())
          message += " " + Utilities::trim(line);
    }
  deallog << name << ": " << message << std::endl;
  if (!entry.empty())
    deallog << "  names '" << entry << "': "
            << (message.find(entry) != std::string::npos ? "yes" : "no")
            << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  check("correct input", correct_input, "", true);
  check("missing material",
        replace("    set Radius = 0.2\n    set Material = mat",
                "    set Radius = 0.2\n    set Material = steel"),
        "Grains/Grain 1/Material");
  check("grain outside the grid",
        replace("set Centre = 0.3, 0.5",
                "set Centre = 0.9, 0.5\n"
                "    set Radius = 0.3"),
        "Grains/Grain 1");
  check("negative density",
        replace("set Density = 2", "set Density = -1"),
        "Density");
  check("unknown shape",
        replace("set Shape = disk", "set Shape = triangle"),
        "Grains/Grain 1/Shape");
  check("bad boundary condition",
        replace("x-: free slip", "x-: sticky"),
        "Background grid/Boundary conditions");
  check("overlapping grains",
        replace("set Centre = 0.75, 0.5", "set Centre = 0.55, 0.5"),
        "Grains/Grain 2",
        true);
}
