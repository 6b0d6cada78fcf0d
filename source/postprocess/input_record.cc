// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_file.h>
#include <grainmpm/particles/grain_list.h>
#include <grainmpm/postprocess/input_record.h>

#include <filesystem>
#include <fstream>
#include <functional>

namespace grainmpm
{
  template <int dim>
  void
  record_inputs(const Parameters<dim>  &parameters,
                const ParameterHandler &prm,
                const std::string      &input_file,
                const MPI_Comm          communicator)
  {
    // The input with its included files expanded (it can be run again as
    // it is), the values of every parameter (as .prm and as .json), the
    // generated grains.
    const std::string &directory = parameters.output.directory;
    std::string        error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::error_code code;
        std::filesystem::create_directories(directory, code);
        if (code || !std::filesystem::is_directory(directory))
          error = InputError("Output/Output directory = " + directory,
                             "cannot create this directory (" +
                               (code ? code.message() :
                                       std::string("a file has its name")) +
                               "). Choose a directory you can write to.")
                    .what();
        const auto write =
          [&](const std::string                         &name,
              const std::function<void(std::ostream &)> &what) {
            if (!error.empty())
              return;
            std::ofstream out(directory + "/" + name);
            bool          failed = false;
            try
              {
                // deal.II's writers throw ExcIO when the stream fails.
                what(out);
              }
            catch (const std::exception &)
              {
                failed = true;
              }
            out.close();
            if (failed || !out)
              error = InputError("Output/Output directory = " + directory,
                                 "cannot write the file '" + name +
                                   "' in it (disk full, or no permission?).")
                        .what();
          };
        // The summary of an earlier run in this directory would be taken
        // for this run's if it stops on an error.
        std::error_code ignored;
        std::filesystem::remove(directory + "/summary.csv", ignored);
        write(original_file_name(input_file),
              [&](std::ostream &out) { out << expand_includes(input_file); });
        write("parameters.prm", [&](std::ostream &out) {
          prm.print_parameters(out, ParameterHandler::PRM);
        });
        write("parameters.json", [&](std::ostream &out) {
          prm.print_parameters(out, ParameterHandler::JSON);
        });
        if (parameters.n_packed_grains > 0)
          write("packing.csv", [&](std::ostream &out) {
            // The generated grains, to be read back as a Grain list file.
            write_grain_list<dim>(
              out,
              std::vector<GrainParameters<dim>>(parameters.grains.end() -
                                                  parameters.n_packed_grains,
                                                parameters.grains.end()));
          });
      }
    throw_on_all_ranks(error, communicator);
  }



  template void
  record_inputs<2>(const Parameters<2> &,
                   const ParameterHandler &,
                   const std::string &,
                   const MPI_Comm);
  template void
  record_inputs<3>(const Parameters<3> &,
                   const ParameterHandler &,
                   const std::string &,
                   const MPI_Comm);
} // namespace grainmpm
