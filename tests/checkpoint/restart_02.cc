// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Checkpoint/restart with another number of MPI ranks (run on two): the
// triangulation and its material points are loaded by p4est on the new
// ranks and repartitioned by their points. The resumed energy.csv must
// agree with the uninterrupted one to round-off (the sums run in another
// order):
// (a) written on two ranks, resumed on one (rank 0 alone);
// (b) written on one rank, resumed on two.
// Cases: the explicit five-grain impact (Von Mises grains, friction) and
// the implicit two-disk collision, each with a checkpoint half-way.
// Explicit steps agree to round-off (measured 1.6e-12 of the largest
// energy); implicit ones to the accuracy of the inexact Newton solve, whose
// Krylov iterations see the round-off (measured 2-4e-8).

#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "../tests.h"

using namespace grainmpm;

/** The numbers of energy.csv in @p directory, row by row (header skipped). */
std::vector<std::vector<double>>
read_energy(const std::string &directory)
{
  std::ifstream                    in(directory + "/energy.csv");
  std::string                      line;
  std::vector<std::vector<double>> rows;
  std::getline(in, line);
  while (std::getline(in, line))
    {
      std::vector<double> row;
      std::istringstream  fields(line);
      std::string         field;
      while (std::getline(fields, field, ','))
        row.push_back(std::stod(field));
      rows.push_back(row);
    }
  return rows;
}



/**
 * The largest difference between @p a and @p b in time (relative to the end
 * time) and kinetic, elastic and total energy (relative to the largest
 * total energy); infinity if the shapes differ.
 */
double
largest_difference(const std::vector<std::vector<double>> &a,
                   const std::vector<std::vector<double>> &b)
{
  if (a.size() != b.size() || a.empty())
    return std::numeric_limits<double>::infinity();
  double energy_scale = 0.;
  for (const auto &row : a)
    energy_scale = std::max(energy_scale, std::abs(row[5]));
  double worst = 0.;
  for (unsigned int r = 0; r < a.size(); ++r)
    {
      worst =
        std::max(worst, std::abs(a[r][1] - b[r][1]) / std::abs(a.back()[1]));
      for (const unsigned int column : {3U, 4U, 5U})
        worst =
          std::max(worst, std::abs(a[r][column] - b[r][column]) / energy_scale);
    }
  return worst;
}



void
write_prm(const std::string &name,
          const std::string &shipped_case,
          const double       end_time,
          const std::string &directory,
          const unsigned int interval,
          const std::string &resume)
{
  std::ofstream prm(name);
  prm << "include " << GRAINMPM_SOURCE_DIR << "/prm/" << shipped_case
      << ".prm\n"
      << "subsection Time stepping\n  set End time = " << end_time << "\nend\n"
      << "subsection Output\n  set Output directory = " << directory
      << "\n  set Test mode = true\n  set Write particles = false\n"
      << "  set Write grid = false\nend\n"
      << "subsection Checkpoint\n  set Steps between checkpoints = " << interval
      << "\n  set Checkpoints kept = 10\n  set Resume from = " << resume
      << "\nend\n"
      << "subsection Load balancing\n  set Steps between repartitioning = "
         "10\nend\n";
}



/**
 * Run @p shipped_case on @p writer, resume it from the checkpoint at step
 * @p resume_step on @p reader, and compare the energy histories. Ranks
 * outside a communicator (MPI_COMM_NULL) wait.
 */
void
check(const std::string &name,
      const std::string &shipped_case,
      const double       end_time,
      const unsigned int interval,
      const unsigned int resume_step,
      const MPI_Comm     writer,
      const MPI_Comm     reader,
      const double       tolerance)
{
  const std::string directory = "results-" + name;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::filesystem::remove_all(directory);
      write_prm(name + ".prm", shipped_case, end_time, directory, interval, "");
      std::ostringstream checkpoint;
      checkpoint << directory << "/checkpoint-" << std::setw(6)
                 << std::setfill('0') << resume_step;
      write_prm(name + "_resumed.prm",
                shipped_case,
                end_time,
                directory,
                interval,
                checkpoint.str());
    }
  MPI_Barrier(MPI_COMM_WORLD);

  if (writer != MPI_COMM_NULL)
    grainmpm::run<2>(name + ".prm", writer);
  MPI_Barrier(MPI_COMM_WORLD);
  const auto uninterrupted = read_energy(directory);
  MPI_Barrier(MPI_COMM_WORLD);

  if (reader != MPI_COMM_NULL)
    grainmpm::run<2>(name + "_resumed.prm", reader);
  MPI_Barrier(MPI_COMM_WORLD);
  const auto   resumed    = read_energy(directory);
  const double difference = largest_difference(uninterrupted, resumed);

  deallog << name << ": " << uninterrupted.size() << " rows, resumed from step "
          << resume_step << std::endl;
  deallog << "  resumed energy.csv = uninterrupted to " << tolerance << ": "
          << (difference < tolerance ? "yes" : "no") << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  AssertThrow(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 2,
              ExcMessage("this test runs on two ranks"));

  // Rank 0 alone.
  MPI_Comm single;
  MPI_Comm_split(MPI_COMM_WORLD,
                 Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0 ?
                   0 :
                   MPI_UNDEFINED,
                 0,
                 &single);

  check("grains_2_to_1",
        "five_grains_explicit",
        20.,
        50,
        100,
        MPI_COMM_WORLD,
        single,
        1e-9);
  check("grains_1_to_2",
        "five_grains_explicit",
        20.,
        50,
        100,
        single,
        MPI_COMM_WORLD,
        1e-9);
  check("disks_2_to_1",
        "two_disks_implicit",
        3.5,
        10,
        20,
        MPI_COMM_WORLD,
        single,
        1e-6);
  check("disks_1_to_2",
        "two_disks_implicit",
        3.5,
        10,
        20,
        single,
        MPI_COMM_WORLD,
        1e-6);

  if (single != MPI_COMM_NULL)
    MPI_Comm_free(&single);
}
