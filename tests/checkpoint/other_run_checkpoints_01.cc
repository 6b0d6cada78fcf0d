// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A fresh run must not replace or delete the checkpoints of another run in
// its output directory. The shipped implicit two disks to t = 1 (11 steps)
// with a checkpoint every 4 steps leave checkpoints 4 and 8; a second fresh
// run in the same directory that writes checkpoints is refused, naming
// Checkpoint/Replace other checkpoints, and leaves them as they were; with
// Replace other checkpoints = true and a checkpoint every 3 steps (1 kept)
// it runs, keeps its own newest one, and the first run's are still there.

#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "../tests.h"

using namespace grainmpm;

const std::string directory = "results-other_run_checkpoints_01";

std::set<std::string>
checkpoints()
{
  std::set<std::string> names;
  for (const auto &entry : std::filesystem::directory_iterator(directory))
    if (entry.path().filename().string().rfind("checkpoint-", 0) == 0)
      names.insert(entry.path().filename().string());
  return names;
}



std::string
run(const std::string &name, const std::string &checkpoint_entries)
{
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::ofstream(name + ".prm")
      << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_implicit.prm\n"
      << "subsection Time stepping\n  set End time = 1\nend\n"
      << "subsection Output\n  set Output directory = " << directory
      << "\n  set Test mode = true\n  set Write particles = false\n"
      << "  set Write grid = false\nend\n"
      << "subsection Checkpoint\n"
      << checkpoint_entries << "end\n";
  MPI_Barrier(MPI_COMM_WORLD);
  try
    {
      grainmpm::run<2>(name + ".prm", MPI_COMM_WORLD);
      return "finished";
    }
  catch (const std::exception &error)
    {
      return error.what();
    }
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::filesystem::remove_all(directory);

  deallog << "first run: "
          << run("first",
                 "  set Steps between checkpoints = 4\n"
                 "  set Checkpoints kept = 3\n")
          << std::endl;
  const std::set<std::string> first = checkpoints();
  deallog << "  checkpoints:";
  for (const auto &name : first)
    deallog << ' ' << name;
  deallog << std::endl;

  deallog << "second fresh run: "
          << run("second", "  set Steps between checkpoints = 3\n")
          << std::endl;
  deallog << "  the first run's checkpoints as they were: "
          << (checkpoints() == first ? "yes" : "no") << std::endl;

  deallog << "third fresh run, Replace other checkpoints = true: "
          << run("third",
                 "  set Steps between checkpoints = 3\n"
                 "  set Checkpoints kept = 1\n"
                 "  set Replace other checkpoints = true\n")
          << std::endl;
  const std::set<std::string> after = checkpoints();
  bool                        kept  = true;
  for (const auto &name : first)
    kept = kept && after.count(name) == 1;
  deallog << "  the first run's checkpoints still there: "
          << (kept ? "yes" : "no")
          << ", checkpoints of the third run: " << after.size() - first.size()
          << std::endl;
}
