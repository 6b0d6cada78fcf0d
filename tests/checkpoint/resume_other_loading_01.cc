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
// The explicit run resumes in a copy of the first run's directory; the
// implicit one in a new, empty directory: its histories start as copies
// of the first run's, cut back to the checkpoint, the first run's files
// are left as they were, and its particles.pvd names the first run's
// particle files up to the checkpoint (as ../results-first/...) and its
// own after it: every file it names exists.
// A third run resumes, also in an empty directory, explicit with
// Time stepping/Mass scaling = 4, which the checkpoint did not have: the
// points' masses are multiplied by 4 on the resume, the explicit step
// doubles (half the steps after the checkpoint, within 10 %), the balance
// residual goes on from its value at the checkpoint (the ledger's
// reference moves with the kinetic energy: over the first step it changes
// by 4 times the unscaled run's change, within 25 %), and the platen work
// after the checkpoint is the unscaled explicit run's within 2 %.
// A fourth run resumes with the platen stopped, Mass scaling = 4 and
// Checkpoint/Scale velocities with the mass = true: the points keep their
// kinetic energy (after the first step it is the checkpoint's within
// 25 %; 0.92, against 3.7 with the velocities kept).

#include <grainmpm/simulator.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

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
      << (scheme != "implicit" ? "  set Scheme = explicit leapfrog\n"
                                 "  set Stress update = USL\n"
                                 "  set Time step = 0\n"
                                 "  set CFL number = 0.25\n" :
                                 "")
      << (scheme == "scaled" || scheme == "settled" ?
            "  set Mass scaling = 4\n" :
            "")
      << "end\n"
      << "subsection Output\n  set Output directory = " << directory
      << "\n  set Test mode = true\n  set Write particles = true\n"
      << "  set Write grid = false\n  set Output interval = 0.05\nend\n"
      << "subsection Checkpoint\n  set Steps between checkpoints = 300\n"
      << "  set Checkpoints kept = 10\n  set Resume from = " << resume
      << (scheme == "settled" ?
            "\n  set Scale velocities with the mass = true" :
            "")
      << "\nend\n";
}



/**
 * The largest difference between the columns of @p a and @p b in the rows
 * up to @p last_step.
 */
double
difference_up_to(const std::map<std::string, std::vector<double>> &a,
                 const std::map<std::string, std::vector<double>> &b,
                 const unsigned int                                last_step)
{
  double worst = 0.;
  for (const auto &[name, values] : a)
    {
      if (b.count(name) == 0 || values.size() <= last_step ||
          b.at(name).size() <= last_step)
        return std::numeric_limits<double>::infinity();
      for (unsigned int r = 0; r <= last_step; ++r)
        worst = std::max(worst, std::abs(values[r] - b.at(name)[r]));
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
  const auto   first           = read_energy("results-first");
  const double checkpoint_time = first.at("time")[checkpoint_step];

  const std::uintmax_t first_energy_size =
    std::filesystem::file_size("results-first/energy.csv");
  const std::uintmax_t first_pvd_size =
    std::filesystem::file_size("results-first/particles.pvd");

  std::vector<double>       platen_work;
  std::vector<unsigned int> steps_after;
  // The change of the balance residual over the first step after the
  // checkpoint (the platen's jump to the new speed is an impact).
  std::vector<double> first_balance_change;
  for (const std::string scheme : {"explicit", "implicit", "scaled"})
    {
      const std::string directory = "results-" + scheme;
      const std::string checkpoint =
        "/checkpoint-" + Utilities::int_to_string(checkpoint_step, 6);
      std::filesystem::remove_all(directory);
      if (scheme == "explicit")
        std::filesystem::copy("results-first",
                              directory,
                              std::filesystem::copy_options::recursive);
      write_prm(scheme + ".prm",
                directory,
                scheme,
                fast,
                end_time,
                (scheme == "explicit" ? directory : "results-first") +
                  checkpoint);
      grainmpm::run<2>(scheme + ".prm", MPI_COMM_WORLD);

      const auto energy = read_energy(directory);
      deallog << scheme << ": energy.csv up to the checkpoint as written: "
              << (difference_up_to(first, energy, checkpoint_step) == 0. ?
                    "yes" :
                    "no")
              << std::endl;

      const std::vector<double> &newton = energy.at("newton_iterations");
      bool scheme_used = energy.at("time").back() > end_time - 1e-12;
      for (unsigned int r = checkpoint_step + 1; r < newton.size(); ++r)
        scheme_used = scheme_used && (scheme == "implicit" ? newton[r] >= 1. :
                                                             newton[r] == 0.);
      steps_after.push_back(newton.size() - 1 - checkpoint_step);
      deallog << scheme << ": " << steps_after.back()
              << " steps after the checkpoint, all of the "
              << (scheme == "implicit" ? "implicit" : "explicit")
              << " scheme: " << (scheme_used ? "yes" : "no") << std::endl;
      const std::vector<double> &balance = energy.at("balance_residual");
      first_balance_change.push_back(balance[checkpoint_step + 1] -
                                     balance[checkpoint_step]);
      if (scheme == "scaled")
        {
          // Mass scaling 4 doubles the explicit step; the points' masses
          // are multiplied by 4 on the resume, and the ledger's reference
          // moves with the kinetic energy, so that the balance residual
          // goes on from its value at the checkpoint: over the first step
          // it changes by what the platen's jump to the new speed costs,
          // 4 times the unscaled run's change (without the move it would
          // change by the kinetic energy's jump, +2.9e-5 against -2.9e-6).
          const double ratio =
            first_balance_change[2] / (4. * first_balance_change[0]);
          deallog << "scaled: steps after the checkpoint / explicit's in "
                  << "(0.45, 0.55): "
                  << (std::abs(double(steps_after[2]) / steps_after[0] - 0.5) <
                          0.05 ?
                        "yes" :
                        "no")
                  << std::endl;
          deallog << "scaled: the balance residual's change over the "
                  << "first step after the checkpoint is 4 times the "
                  << "unscaled run's within 25 %: "
                  << (std::abs(ratio - 1.) < 0.25 ? "yes" : "no") << std::endl;
          if (std::getenv("GRAINMPM_VERBOSE") != nullptr)
            std::cout << "first balance changes " << first_balance_change[0]
                      << ' ' << first_balance_change[2] << " ratio " << ratio
                      << " steps " << steps_after[2] << " / " << steps_after[0]
                      << std::endl;
        }

      // The platen (grain 2) at the checkpoint, from its last output
      // before it, and at the end.
      const auto grains       = read_csv(directory + "/grains.csv");
      double     y_checkpoint = 0., y_end = 0., t_end = 0.;
      for (unsigned int r = 0; r < grains.at("time").size(); ++r)
        if (grains.at("grain")[r] == 2.)
          {
            const double t = grains.at("time")[r], y = grains.at("centre_y")[r];
            if (t < checkpoint_time)
              y_checkpoint = y - slow * (checkpoint_time - t);
            t_end = t;
            y_end = y;
          }
      deallog << scheme << ": platen moved at the new speed after the "
              << "checkpoint (to 1e-10): "
              << (std::abs(y_end - (y_checkpoint -
                                    fast * (t_end - checkpoint_time))) < 1e-10 ?
                    "yes" :
                    "no")
              << std::endl;

      if (scheme == "implicit")
        {
          deallog << "implicit: the first run's energy.csv and particles.pvd "
                  << "unchanged: "
                  << (std::filesystem::file_size("results-first/energy.csv") ==
                            first_energy_size &&
                          std::filesystem::file_size(
                            "results-first/particles.pvd") == first_pvd_size ?
                        "yes" :
                        "no")
                  << std::endl;
          // The files particles.pvd names, relative to its directory.
          std::ifstream pvd(directory + "/particles.pvd");
          std::string   line;
          unsigned int  named = 0, found = 0, earlier = 0;
          while (std::getline(pvd, line))
            {
              const std::size_t at = line.find("file=\"");
              if (at == std::string::npos)
                continue;
              const std::size_t begin = at + 6;
              const std::string file =
                line.substr(begin, line.find('"', begin) - begin);
              ++named;
              found += std::filesystem::exists(directory + "/" + file);
              earlier += file.rfind("../results-first/", 0) == 0;
            }
          deallog << "implicit: particles.pvd names " << named << " files, "
                  << earlier << " of them the first run's; all exist: "
                  << (found == named && named > earlier && earlier > 0 ? "yes" :
                                                                         "no")
                  << std::endl;
        }

      const std::vector<double> &work = energy.at("boundary_work");
      platen_work.push_back(work.back() - work[checkpoint_step]);
    }
  deallog << "platen work after the checkpoint, implicit / explicit within "
          << "2 %: "
          << (std::abs(platen_work[1] / platen_work[0] - 1.) < 0.02 ? "yes" :
                                                                      "no")
          << std::endl;
  deallog << "platen work after the checkpoint, mass scaling 4 / explicit "
          << "within 2 %: "
          << (std::abs(platen_work[2] / platen_work[0] - 1.) < 0.02 ? "yes" :
                                                                      "no")
          << std::endl;

  // The platen stopped at the checkpoint, Mass scaling 4 with Scale
  // velocities with the mass: the points keep their kinetic energy, so
  // that after the first step it is the checkpoint's within 25 % (with
  // kept velocities it is 4 times it, within 25 %: checked by hand).
  std::filesystem::remove_all("results-settled");
  write_prm("settled.prm",
            "results-settled",
            "settled",
            0.,
            checkpoint_time + 0.001,
            "results-first/checkpoint-" +
              Utilities::int_to_string(checkpoint_step, 6));
  grainmpm::run<2>("settled.prm", MPI_COMM_WORLD);
  const auto   settled = read_energy("results-settled");
  const double kinetic_ratio =
    settled.at("kinetic_energy")[checkpoint_step + 1] /
    first.at("kinetic_energy")[checkpoint_step];
  deallog << "settled: the kinetic energy after the first step after the "
          << "checkpoint is the checkpoint's within 25 %: "
          << (std::abs(kinetic_ratio - 1.) < 0.25 ? "yes" : "no") << std::endl;
  if (std::getenv("GRAINMPM_VERBOSE") != nullptr)
    std::cout << "settled kinetic ratio " << kinetic_ratio << std::endl;
  if (std::getenv("GRAINMPM_VERBOSE") != nullptr)
    std::cout << "platen work ratios " << platen_work[1] / platen_work[0] << ' '
              << platen_work[2] / platen_work[0] << std::endl;
}
