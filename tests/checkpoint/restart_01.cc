// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Checkpoint/restart (subsection Checkpoint), on one and on two MPI ranks
// (the same output): a run writes a checkpoint
// every N steps; a second run resumed from one of them in the same output
// directory cuts the CSV histories back to the checkpoint and
// continues. The files at the end must be byte-for-byte those of the
// uninterrupted run:
// (a) the implicit two-disk collision (prm/two_disks_implicit.prm) with
//     each step's contact status started from the last step's (kept in
//     the checkpoint; the disks touch at step 28), checkpoints every 4
//     steps, resumed from step 28 of 37;
// (a') the one-disk slow compression (prm/slow_compression_one_disk.prm)
//     with Maximum time step = 0.05, whose steps the error estimate keeps
//     near the nominal one, from the points' accelerations of the last
//     step (kept with the points) and the length of the last step (kept
//     in the checkpoint), and whose steps after a quasi-static one use
//     Quasi-static theta (whether the last step was quasi-static is kept
//     in the checkpoint; steps 19 to 32 use it), checkpoints every 8
//     steps, resumed from step 24 of 32;
// (b) the explicit single grain between walls to t = 0.3, resumed from
//     step 1400, shortly after the first wall impact;
// (b') in 3D, the sphere of tests/runs/sphere_rebound_3d.prm hitting the
//     x+ wall, caught up by a smaller sphere (a pair contact), resumed from
//     step 600;
// (c) only the newest 'Checkpoints kept' remain, and a half-written
//     checkpoint-NNNNNN.tmp left by a killed run does not disturb a resume.

#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "../tests.h"

using namespace grainmpm;

std::string
contents(const std::string &filename)
{
  std::ifstream      in(filename, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}



std::string
yes_no(const bool condition)
{
  return condition ? "yes" : "no";
}



template <int dim>
void
check(const std::string &name,
      const std::string &shipped_case,
      const std::string &extra,
      const unsigned int interval,
      const unsigned int resume_step)
{
  const std::string directory = "results-" + name;
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (root)
    {
      std::filesystem::remove_all(directory);
      std::ofstream prm(name + ".prm");
      prm << "include " << GRAINMPM_SOURCE_DIR << "/" << shipped_case
          << ".prm\n"
          << extra
          << "subsection Output\n  set Output directory = " << directory
          << "\n  set Test mode = true\n  set Output interval = 0.1\n"
          << "  set Write particles = false\n  set Write grid = false\nend\n"
          << "subsection Checkpoint\n  set Steps between checkpoints = "
          << interval << "\n  set Checkpoints kept = 3\nend\n";
    }
  MPI_Barrier(MPI_COMM_WORLD);
  grainmpm::run<dim>(name + ".prm", MPI_COMM_WORLD);
  const std::string energy   = contents(directory + "/energy.csv");
  const std::string grains   = contents(directory + "/grains.csv");
  const std::string walls    = contents(directory + "/walls.csv");
  const std::string contacts = contents(directory + "/contacts.csv");

  unsigned int n_checkpoints = 0;
  for (const auto &entry : std::filesystem::directory_iterator(directory))
    if (entry.path().filename().string().rfind("checkpoint-", 0) == 0)
      ++n_checkpoints;

  // A killed run's half-written checkpoint.
  MPI_Barrier(MPI_COMM_WORLD);
  std::ostringstream checkpoint;
  checkpoint << directory << "/checkpoint-" << std::setw(6) << std::setfill('0')
             << resume_step;
  if (root)
    {
      std::filesystem::create_directories(directory + "/checkpoint-999999.tmp");
      std::ofstream(directory + "/checkpoint-999999.tmp/state") << "garbage";
      std::ofstream prm(name + "_resumed.prm");
      prm << "include " << name << ".prm\n"
          << "subsection Checkpoint\n  set Resume from = " << checkpoint.str()
          << "\nend\n";
    }
  MPI_Barrier(MPI_COMM_WORLD);
  grainmpm::run<dim>(name + "_resumed.prm", MPI_COMM_WORLD);
  unsigned int n_after = 0;
  for (const auto &entry : std::filesystem::directory_iterator(directory))
    if (entry.path().filename().string().rfind("checkpoint-", 0) == 0 &&
        entry.path().extension() != ".tmp")
      ++n_after;

  deallog << name << ": " << n_checkpoints << " checkpoints kept (3 asked)"
          << std::endl;
  deallog << "  3 kept also after the resumed run rewrote its checkpoints: "
          << yes_no(n_after == 3) << std::endl;
  deallog << "  resumed energy.csv = uninterrupted, byte for byte: "
          << yes_no(contents(directory + "/energy.csv") == energy &&
                    energy.size() > 1000)
          << std::endl;
  deallog << "  resumed grains.csv = uninterrupted, byte for byte: "
          << yes_no(contents(directory + "/grains.csv") == grains &&
                    grains.size() > 100)
          << std::endl;
  // The contact sums of the interval and the rigid centres are in the
  // checkpoint.
  deallog << "  resumed walls.csv and contacts.csv = uninterrupted, byte for "
             "byte: "
          << yes_no(contents(directory + "/walls.csv") == walls &&
                    contents(directory + "/contacts.csv") == contacts &&
                    walls.size() > 1000)
          << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  check<2>("disks",
           "prm/two_disks_implicit",
           "subsection Nonlinear solver\n"
           "  set Contact status from last step = true\n"
           "end\n",
           4,
           28);
  check<2>("grown",
           "prm/slow_compression_one_disk",
           "subsection Time stepping\n  set Maximum time step = 0.05\nend\n",
           8,
           24);
  check<2>("grain",
           "prm/single_grain_rebound_explicit",
           "subsection Time stepping\n  set End time = 0.3\nend\n",
           700,
           1400);
  // 3D: the sphere rebound, with a smaller sphere catching up with it.
  check<3>("spheres",
           "tests/runs/sphere_rebound_3d",
           "subsection Grains\n  subsection Grain 2\n"
           "    set Shape = sphere\n    set Centre = 0.12, 0.5, 0.5\n"
           "    set Radius = 0.1\n    set Material = rubber\n"
           "    set Initial velocity = 2; 0; 0\n  end\nend\n",
           200,
           600);
}
