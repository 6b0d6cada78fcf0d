// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A run resumes only from a checkpoint it can trust, and says why not
// before reading any of it. The shipped implicit two disks to t = 1 (11
// steps) with a checkpoint every 4 steps leave checkpoint-000008. Copies of
// it are damaged (a flipped byte in the material points, the state cut to
// half, a data file or the manifest deleted; the material points' data or
// the cells' data cut short with a manifest that agrees, as a write that
// failed unnoticed left them), and it is resumed with other parameters (another
// grid, more material points per cell): each resume is refused naming
// Checkpoint/Resume from and what is wrong (these used to resume with nonsense,
// segfault, or give raw library text). The intact checkpoint resumes to the
// end. Sizes and checksums in the messages are replaced by N and X (they depend
// on the number of ranks).

#include <grainmpm/postprocess/checkpoint_files.h>
#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "../tests.h"

using namespace grainmpm;

const std::string directory  = "results-resume_checks_01";
const std::string checkpoint = directory + "/checkpoint-000008";



// Run NAME.prm: the case with @p entries, output in @p output.
std::string
run(const std::string &name,
    const std::string &entries,
    const std::string &output = "")
{
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::ofstream(name + ".prm")
      << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_implicit.prm\n"
      << "subsection Time stepping\n  set End time = 1\nend\n"
      << "subsection Output\n  set Output directory = "
      << (output.empty() ? directory + "-output-" + name : output)
      << "\n  set Test mode = true\n  set Write particles = false\n"
      << "  set Write grid = false\nend\n"
      << entries;
  MPI_Barrier(MPI_COMM_WORLD);
  try
    {
      grainmpm::run<2>(name + ".prm", MPI_COMM_WORLD);
      return "finished";
    }
  catch (const std::exception &error)
    {
      std::string message = error.what();
      message = std::regex_replace(message, std::regex("[0-9a-f]{16}"), "X");
      message = std::regex_replace(message,
                                   std::regex("has [0-9]+ bytes where [0-9]+"),
                                   "has N bytes where M");
      return message;
    }
}



// A copy of the checkpoint, damaged by @p damage (rank 0).
template <typename Damage>
std::string
copy(const std::string &name, const Damage &damage)
{
  const std::string target = directory + "-" + name;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::filesystem::remove_all(target);
      std::filesystem::copy(checkpoint, target);
      damage(target);
    }
  MPI_Barrier(MPI_COMM_WORLD);
  return "subsection Checkpoint\n  set Resume from = " + target + "\nend\n";
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    for (const auto &entry : std::filesystem::directory_iterator("."))
      if (entry.path().filename().string().rfind("results-resume_checks_01",
                                                 0) == 0)
        std::filesystem::remove_all(entry.path());
  MPI_Barrier(MPI_COMM_WORLD);

  deallog << "first run: "
          << run("first",
                 "subsection Checkpoint\n"
                 "  set Steps between checkpoints = 4\nend\n",
                 directory)
          << std::endl;

  deallog << "flipped byte: "
          << run("flipped",
                 copy("flipped",
                      [](const std::string &target) {
                        std::fstream file(target + "/grid_variable.data",
                                          std::ios::in | std::ios::out |
                                            std::ios::binary);
                        file.seekg(0, std::ios::end);
                        const std::streamoff middle = file.tellg() / 2;
                        char                 byte   = 0;
                        file.seekg(middle);
                        file.get(byte);
                        file.seekp(middle);
                        file.put(static_cast<char>(byte ^ 0x10));
                      }))
          << std::endl;
  deallog << "state cut to half: "
          << run("truncated",
                 copy("truncated",
                      [](const std::string &target) {
                        const std::string state = target + "/state";
                        std::filesystem::resize_file(
                          state, std::filesystem::file_size(state) / 2);
                      }))
          << std::endl;
  deallog << "data file deleted: "
          << run("deleted",
                 copy("deleted",
                      [](const std::string &target) {
                        std::filesystem::remove(target + "/grid_fixed.data");
                      }))
          << std::endl;
  deallog << "manifest deleted: "
          << run("no_manifest",
                 copy("no_manifest",
                      [](const std::string &target) {
                        std::filesystem::remove(target + "/manifest");
                      }))
          << std::endl;

  // Cut @p file to @p size bytes and write a manifest that agrees.
  const auto cut_with_manifest = [](const std::string   &file,
                                    const std::uintmax_t size) {
    return [file, size](const std::string &target) {
      std::string fingerprint;
      CheckpointFiles::check_manifest(target, fingerprint);
      std::filesystem::resize_file(target + "/" + file, size);
      std::uintmax_t total = 0;
      std::ofstream(target + "/manifest")
        << CheckpointFiles::make_manifest(target, fingerprint, total);
    };
  };
  deallog << "data file written empty: "
          << run("empty_data",
                 copy("empty_data", cut_with_manifest("grid_variable.data", 0)))
          << std::endl;
  deallog << "cells' data one byte short: "
          << run("short_cells",
                 copy("short_cells",
                      cut_with_manifest("grid_fixed.data",
                                        std::filesystem::file_size(
                                          checkpoint + "/grid_fixed.data") -
                                          1)))
          << std::endl;

  const std::string resume =
    "subsection Checkpoint\n  set Resume from = " + checkpoint + "\nend\n";
  deallog << "another grid: "
          << run("other_grid",
                 resume + "subsection Background grid\n"
                          "  set Number of cells = 40, 40\nend\n")
          << std::endl;
  deallog << "other material points: "
          << run("other_points",
                 resume + "subsection Material points\n"
                          "  set Particles per cell = 3\nend\n")
          << std::endl;
  deallog << "intact: " << run("intact", resume, directory) << std::endl;
}
