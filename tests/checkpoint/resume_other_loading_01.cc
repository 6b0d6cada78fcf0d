// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A checkpoint is resumed with other loading and another scheme: what a
// user does to compact a packing once and then load it in several ways.
// Checkpoint/Resume from checks the grid, the materials and the grains,
// not the contact law, the loading or the time stepping.
//
// The disk of prm/slow_compression_one_disk.prm is compressed by its
// platen (V = 0.037) with the explicit leapfrog to t = 0.1, with a
// checkpoint every 300 steps. From the checkpoint at step 600 it is loaded
// on at twice the platen speed to t = 0.2, (a) explicit, (b) with the
// shipped implicit theta = 1/2 at 100 times the explicit step. Checked:
// - both resumed histories repeat the first run's energy.csv up to the
//   checkpoint;
// - the platen moves at the new speed from the checkpoint on (its centre
//   of mass in grains.csv);
// - the resumed steps are those of the new scheme (Newton iterations in
//   energy.csv: none explicit, at least one each implicit step);
// - the two schemes agree on the platen work from the checkpoint to the
//   end within 2 %.

#include <grainmpm/simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../tests.h"

using namespace grainmpm;

/** The rows of the CSV file @p file as numbers, with its column names. */
std::pair<std::vector<std::string>, std::vector<std::vector<double>>>
read_csv(const std::string &file)
{
  std::ifstream                    in(file);
  std::string                      line, field;
  std::vector<std::string>         names;
  std::vector<std::vector<double>> rows;
  std::getline(in, line);
  std::istringstream header(line);
  while (std::getline(header, field, ','))
    names.push_back(field.substr(0, field.find(" [")));
  while (std::getline(in, line))
    {
      std::vector<double> row;
      std::istringstream  fields(line);
      while (std::getline(fields, field, ','))
        row.push_back(std::stod(field));
      rows.push_back(row);
    }
  return {names, rows};
}



unsigned int
column(const std::vector<std::string> &names, const std::string &name)
{
  const auto it = std::find(names.begin(), names.end(), name);
  AssertThrow(it != names.end(), ExcMessage("no column " + name));
  return it - names.begin();
}



void
write_prm(const std::string &name,
          const std::string &directory,
          const std::string &scheme,
          const double       speed,
          const double       end_time,
          const std::string &resume)
{
  std::ofstream prm(name);
  prm << "include " << GRAINMPM_SOURCE_DIR
      << "/prm/slow_compression_one_disk.prm\n"
      << "subsection Grains\n  subsection Platen\n"
      << "    set Prescribed velocity = 0; " << -speed << "\n  end\nend\n"
      << "subsection Time stepping\n  set End time = " << end_time << '\n'
      << (scheme == "explicit" ? "  set Scheme = explicit leapfrog\n"
                                 "  set Stress update = USL\n"
                                 "  set Time step = 0\n"
                                 "  set CFL number = 0.25\n" :
                                 "")
      << "end\n"
      << "subsection Output\n  set Output directory = " << directory
      << "\n  set Test mode = true\n  set Write particles = false\n"
      << "  set Write grid = false\n  set Output interval = 0.05\nend\n"
      << "subsection Checkpoint\n  set Steps between checkpoints = 300\n"
      << "  set Checkpoints kept = 10\n  set Resume from = " << resume
      << "\nend\n";
}



/** The largest difference of the energy.csv rows up to @p last_step. */
double
difference_up_to(const std::vector<std::vector<double>> &a,
                 const std::vector<std::vector<double>> &b,
                 const unsigned int                      last_step)
{
  double worst = 0.;
  for (unsigned int r = 0; r <= last_step; ++r)
    {
      if (r >= a.size() || r >= b.size() || a[r].size() != b[r].size())
        return std::numeric_limits<double>::infinity();
      for (unsigned int c = 0; c < a[r].size(); ++c)
        worst = std::max(worst, std::abs(a[r][c] - b[r][c]));
    }
  return worst;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const unsigned int checkpoint_step = 600;
  const double       slow = 0.037, fast = 0.074, end_time = 0.2;

  std::filesystem::remove_all("results-first");
  write_prm("first.prm", "results-first", "explicit", slow, 0.1, "");
  grainmpm::run<2>("first.prm", MPI_COMM_WORLD);
  const auto [names, first]    = read_csv("results-first/energy.csv");
  const double checkpoint_time = first[checkpoint_step][column(names, "time")];

  std::vector<double> platen_work;
  for (const std::string scheme : {"explicit", "implicit"})
    {
      const std::string directory = "results-" + scheme;
      std::filesystem::remove_all(directory);
      std::filesystem::copy("results-first",
                            directory,
                            std::filesystem::copy_options::recursive);
      write_prm(scheme + ".prm",
                directory,
                scheme,
                fast,
                end_time,
                directory + "/checkpoint-000600");
      grainmpm::run<2>(scheme + ".prm", MPI_COMM_WORLD);

      const auto [energy_names, energy] = read_csv(directory + "/energy.csv");
      deallog << scheme << ": energy.csv up to the checkpoint as written: "
              << (difference_up_to(first, energy, checkpoint_step) == 0. ?
                    "yes" :
                    "no")
              << std::endl;

      const unsigned int newton = column(energy_names, "newton_iterations");
      bool               scheme_used = energy.back()[1] > end_time - 1e-12;
      for (unsigned int r = checkpoint_step + 1; r < energy.size(); ++r)
        scheme_used =
          scheme_used && (scheme == "explicit" ? energy[r][newton] == 0. :
                                                 energy[r][newton] >= 1.);
      deallog << scheme << ": " << energy.size() - 1 - checkpoint_step
              << " steps after the checkpoint, all of the " << scheme
              << " scheme: " << (scheme_used ? "yes" : "no") << std::endl;

      // The platen (grain 2) at the checkpoint, from its last output
      // before it, and at the end.
      const auto [grain_names, grains] = read_csv(directory + "/grains.csv");
      const unsigned int time          = column(grain_names, "time");
      const unsigned int y             = column(grain_names, "centre_y");
      double             y_checkpoint = 0., y_end = 0., t_end = 0.;
      for (const auto &row : grains)
        if (row[column(grain_names, "grain")] == 2.)
          {
            if (row[time] < checkpoint_time)
              y_checkpoint = row[y] - slow * (checkpoint_time - row[time]);
            t_end = row[time];
            y_end = row[y];
          }
      deallog << scheme << ": platen moved at the new speed after the "
              << "checkpoint (to 1e-10): "
              << (std::abs(y_end - (y_checkpoint -
                                    fast * (t_end - checkpoint_time))) < 1e-10 ?
                    "yes" :
                    "no")
              << std::endl;

      const unsigned int work = column(energy_names, "boundary_work");
      platen_work.push_back(energy.back()[work] -
                            energy[checkpoint_step][work]);
    }
  deallog << "platen work after the checkpoint, implicit / explicit within "
          << "2 %: "
          << (std::abs(platen_work[1] / platen_work[0] - 1.) < 0.02 ? "yes" :
                                                                      "no")
          << std::endl;
}
