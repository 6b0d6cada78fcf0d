// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Output files that cannot be written stop the run with a message that
// names the file and the parameter, on every rank (on two ranks rank 0
// writes the files, and both must stop: no hang):
// - particles.pvd is written to particles.pvd.tmp and renamed; here
//   particles.pvd.tmp is a directory, and particles.pvd is left alone;
// - grains.csv is a link to /dev/full: its header cannot be written.

#include <grainmpm/simulator.h>

#include <filesystem>

#include "../tests.h"

using namespace dealii;

void
run_into(const std::string &name, const std::string &blocked)
{
  const std::string directory = "results-" + name;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::filesystem::remove_all(directory);
      std::filesystem::create_directories(directory);
      if (blocked == "particles.pvd.tmp")
        std::filesystem::create_directory(directory + "/" + blocked);
      else
        std::filesystem::create_symlink("/dev/full", directory + "/" + blocked);
      std::ofstream(name + ".prm")
        << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_explicit.prm\n"
        << "subsection Time stepping\n  set End time = 0.01\nend\n"
        << "subsection Output\n  set Output directory = " << directory
        << "\n  set Test mode = true\nend\n";
    }
  MPI_Barrier(MPI_COMM_WORLD);
  try
    {
      grainmpm::run<2>(name + ".prm", MPI_COMM_WORLD);
      deallog << "no error" << std::endl;
    }
  catch (const std::exception &error)
    {
      deallog << error.what() << std::endl;
    }
  deallog << "particles.pvd exists: "
          << std::filesystem::exists(directory + "/particles.pvd") << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  run_into("record_blocked", "particles.pvd.tmp");
  run_into("disk_full", "grains.csv");
}
