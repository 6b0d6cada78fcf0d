// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A record file that cannot be written: particles.pvd is written to
// particles.pvd.tmp and renamed, and here particles.pvd.tmp is a directory.
// The run must stop with a message that names the file and the parameter,
// and leave the particles.pvd of the previous output (none here) alone; on
// two ranks, rank 0 writes the record and both must stop (no hang).

#include <grainmpm/simulator.h>

#include <filesystem>

#include "../tests.h"

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  const std::string directory = "results-output_write_error_01";
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::filesystem::remove_all(directory);
      std::filesystem::create_directories(directory + "/particles.pvd.tmp");
      std::ofstream("output_write_error_01.prm")
        << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_explicit.prm\n"
        << "subsection Time stepping\n  set End time = 0.01\nend\n"
        << "subsection Output\n  set Output directory = " << directory
        << "\n  set Test mode = true\nend\n";
    }
  MPI_Barrier(MPI_COMM_WORLD);
  try
    {
      grainmpm::run<2>("output_write_error_01.prm", MPI_COMM_WORLD);
      deallog << "no error" << std::endl;
    }
  catch (const std::exception &error)
    {
      deallog << error.what() << std::endl;
    }
  deallog << "particles.pvd exists: "
          << std::filesystem::exists(directory + "/particles.pvd") << std::endl;
}
