// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// grainmpm: multi-grain Material Point Method after Cummins & Brackbill.
// Usage: grainmpm [--quiet] case.prm | --print-parameters [2|3] [FORMAT] |
//        --check-parameters case.prm | --version | --help

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_file.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/particles/random_packing.h>
#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <iostream>
#include <sstream>

namespace
{
  using namespace grainmpm;

  void
  print_usage(std::ostream &out)
  {
    out << "Usage: grainmpm [--quiet] CASE.prm     run a case (--quiet: no "
           "progress lines)\n"
        << "       grainmpm --check-parameters CASE.prm   parse and check "
           "only\n"
        << "       grainmpm --print-parameters [2|3] [prm|json|xml]\n"
        << "                                              print every "
           "parameter with its documentation\n"
        << "       grainmpm --version                     print the "
           "versions of grainmpm and deal.II\n"
        << "       grainmpm --help\n"
        << "CASE may be a .prm, .json or .xml file (the formats of "
           "--print-parameters;\na run writes its parameters as "
           "parameters.prm and parameters.json).\n";
  }



  // A command line that grainmpm does not understand: the reason, then the
  // usage, on standard error; exit code 1.
  int
  usage_error(const std::string &reason)
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        std::cerr << "grainmpm: error: " << reason << ".\n";
        print_usage(std::cerr);
      }
    return 1;
  }



  template <int dim>
  void
  print_parameters(const ParameterHandler::OutputStyle style)
  {
    ParameterHandler prm;
    Parameters<dim>  parameters;
    parameters.declare(prm, {"example material"}, {"Grain 1"});
    prm.print_parameters(std::cout, style);
  }



  template <int dim>
  void
  check_parameters(const std::string &filename)
  {
    ParameterHandler prm;
    Parameters<dim>  parameters;
    parameters.parse(filename, prm);
    add_random_packing(parameters);
    parameters.apply_mass_scaling();

    // The checks of a run before its first step: the grains on the grid
    // (overlaps, grains outside the grid, function expressions and their
    // values) and the time step.
    BackgroundGrid<dim>             grid(parameters.grid, MPI_COMM_WORLD);
    Particles::ParticleHandler<dim> particle_handler(
      grid.get_triangulation(),
      grid.get_mapping(),
      MaterialPointLayout<dim>::n_properties);
    std::vector<std::unique_ptr<ConstitutiveModel<dim>>> materials;
    for (const auto &material : parameters.materials)
      materials.emplace_back(create_constitutive_model<dim>(
        material, parameters.physics.two_dimensional_model));
    const std::vector<GrainInfo<dim>> grains =
      GrainGenerator<dim>(parameters).generate(grid, particle_handler);
    const TimeStepController controller(
      parameters.time_stepping,
      parameters.nonlinear_solver.max_iterations,
      grid.minimum_cell_size(),
      largest_wave_speed(grains, materials));

    std::cout << filename << ": " << dim << "D, " << parameters.materials.size()
              << " materials, " << parameters.grains.size()
              << " grains: parameters OK" << std::endl;
  }
} // namespace



int
main(int argc, char *argv[])
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::vector<std::string>                 arguments(argv + 1, argv + argc);
  // --quiet (-q) may stand anywhere: no header, no progress lines and no
  // Newton lines (Nonlinear solver/Verbose).
  const auto quiet_option =
    std::find_if(arguments.begin(),
                 arguments.end(),
                 [](const std::string &argument) {
                   return argument == "--quiet" || argument == "-q";
                 });
  const bool quiet = quiet_option != arguments.end();
  if (quiet)
    arguments.erase(quiet_option);
  try
    {
      if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h")
        {
          print_usage(arguments.empty() ? std::cerr : std::cout);
          return arguments.empty() ? 1 : 0;
        }
      if (arguments[0] == "--version")
        {
          if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            std::cout << "grainmpm " << GRAINMPM_VERSION << " (deal.II "
                      << DEAL_II_PACKAGE_VERSION << ")" << std::endl;
          return 0;
        }
      if (arguments[0] == "--print-parameters")
        {
          // [2|3] [prm|json|xml], each optional, in this order.
          std::size_t next      = 1;
          std::string dimension = "2", format = "prm";
          if (next < arguments.size() &&
              (arguments[next] == "2" || arguments[next] == "3"))
            dimension = arguments[next++];
          if (next < arguments.size() &&
              (arguments[next] == "prm" || arguments[next] == "json" ||
               arguments[next] == "xml"))
            format = arguments[next++];
          if (next != arguments.size())
            return usage_error("--print-parameters takes the dimension (2 or "
                               "3, default 2) and the format (prm, json or "
                               "xml, default prm), not '" +
                               arguments[next] + "'");
          const ParameterHandler::OutputStyle style =
            format == "json" ? ParameterHandler::JSON :
            format == "xml"  ? ParameterHandler::XML :
                               ParameterHandler::PRM;
          if (dimension == "3")
            print_parameters<3>(style);
          else
            print_parameters<2>(style);
          return 0;
        }
      if (arguments[0] == "--check-parameters")
        {
          if (arguments.size() != 2)
            return usage_error("--check-parameters takes one parameter file");
          if (read_dimension(arguments[1]) == 2)
            check_parameters<2>(arguments[1]);
          else
            check_parameters<3>(arguments[1]);
          return 0;
        }
      if (arguments[0][0] == '-')
        return usage_error("unknown option '" + arguments[0] + "'");
      if (arguments.size() != 1)
        return usage_error("a run takes one parameter file, not " +
                           std::to_string(arguments.size()) + " arguments");
      if (read_dimension(arguments[0]) == 2)
        run<2>(arguments[0], MPI_COMM_WORLD, quiet);
      else
        run<3>(arguments[0], MPI_COMM_WORLD, quiet);
    }
  catch (const RunStopped &stopped)
    {
      // SIGTERM or SIGINT: the run wrote its output (and checkpoint) and
      // ends with the exit status of a process killed by the signal.
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::cerr << "\ngrainmpm: " << stopped.what() << std::endl;
      return 128 + stopped.signal;
    }
  catch (const InputError &error)
    {
      // Input errors are seen by every rank alike (the parameter file) or
      // made so (throw_on_all_ranks()): rank 0 reports.
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::cerr << "\ngrainmpm: error: " << error.what() << std::endl;
      return 1;
    }
  catch (const dealii::ExceptionBase &exception)
    {
      // Pattern mismatches and other parameter-file errors of deal.II: print
      // only the part that names the entry, not the source location.
      // deal.II names the file and line: add the subsection path, and name
      // the file by its base name (the user knows which file they passed;
      // test outputs must not depend on paths).
      std::ostringstream message;
      exception.print_info(message);
      std::string       text = message.str();
      std::string       where;
      const std::size_t line_start = text.find("Line <");
      const std::size_t open       = text.find("of file <");
      if (line_start != std::string::npos && open != std::string::npos)
        {
          const std::size_t  close = text.find('>', open);
          const std::string  file  = text.substr(open + 9, close - open - 9);
          const unsigned int line =
            std::stoi(text.substr(line_start + 6, open - line_start - 6));
          where = grainmpm::subsection_path_at_line(file, line);
          const std::size_t slash = file.rfind('/');
          if (slash != std::string::npos)
            text.erase(open + 9, slash + 1);
        }
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
        return 1;
      if (!where.empty())
        std::cerr << "\ngrainmpm: error in the input, in subsection " << where
                  << ":\n"
                  << text << std::endl;
      else
        std::cerr << "\ngrainmpm: error in the input:\n" << text << std::endl;
      return 1;
    }
  catch (const std::exception &exception)
    {
      // Anything else may have happened on one rank only: stop them all.
      std::cerr << "\ngrainmpm: error: " << exception.what() << std::endl;
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        MPI_Abort(MPI_COMM_WORLD, 1);
      return 1;
    }
  return 0;
}
