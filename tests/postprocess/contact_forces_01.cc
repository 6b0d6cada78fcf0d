// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// contacts.csv and the contact columns of grains.csv.
// - The two-disk collision (prm/two_disks_explicit.prm and
//   prm/two_disks_implicit.prm, R = 0.2, 20 x 20 cells): the time integral
//   of the pair's mean force (force times output interval) equals each
//   disk's momentum change, and the force is zero before the disks meet
//   and after they have parted (a force below 1e-6 of the largest counts
//   as zero); the gap between the surfaces at the first and last interval
//   with a force is printed in cells (without the gap check the grid
//   contact starts when the disks' points share nodes, some two cells
//   apart). The coordination number is 1 while they touch.
// - A disk (R = 0.1 = 8 h) on a rigid slab with Coulomb friction under
//   gravity tilted by 20 degrees, starting at rest on it, with the gap
//   check (explicit, to t = 0.8): with mu = 0.3 it rolls, the pair force
//   stays inside the friction cone (|F_t| / (mu F_n) about 0.5; rolling
//   needs tan(20 deg) / 3 / mu = 0.40) and the rotation of grains.csv
//   follows the rolling distance, -R theta / dx = 1 less the slip; with
//   mu = 0.05 it slides, the contact slips (mobilised friction 1) and the
//   disk turns less. With the disk read from its shape (the default) the
//   rolling contact is one or two nodes whose tangential impulses partly
//   cancel: the sum of their magnitudes, mobilised friction, is 0.85 of
//   mu times the normal impulse, and the slip share counts 65 % of the
//   normal impulse at nodes at Coulomb's bound (0.53 and 21 % with
//   `Contact/Shape gap = false` and the disk dropped from h/8, as before
//   2026-12-07).

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

namespace
{
  void
  collide(const std::string &scheme)
  {
    const std::string name = "two_disks_" + scheme;
    run_case(name,
             "include " GRAINMPM_SOURCE_DIR "/prm/" + name +
               ".prm\nsubsection Output\n  set Output interval = 0.1\nend\n");
    const auto contacts = read_csv("results-" + name + "/contacts.csv");
    const auto grains   = read_csv("results-" + name + "/grains.csv");
    const auto disk_1   = grain_rows(grains, 1);
    const auto disk_2   = grain_rows(grains, 2);

    // Impulse on disk 2 from disk 1: sum of mean force times interval.
    const std::vector<double> &times      = disk_1.at("time");
    double                     impulse[2] = {0., 0.}, peak = 0.;
    for (unsigned int r = 0; r < contacts.at("time").size(); ++r)
      {
        const double t        = contacts.at("time")[r];
        const auto   i        = std::find(times.begin(), times.end(), t);
        const double interval = t - *(i - 1);
        impulse[0] += contacts.at("force_x")[r] * interval;
        impulse[1] += contacts.at("force_y")[r] * interval;
        peak = std::max(peak, contacts.at("normal_force")[r]);
      }
    const double m = disk_2.at("mass")[0];
    double       change_1[2], change_2[2];
    for (unsigned int d = 0; d < 2; ++d)
      {
        const std::string v = std::string("velocity_") + "xy"[d];
        change_1[d]         = m * (disk_1.at(v).back() - disk_1.at(v).front());
        change_2[d]         = m * (disk_2.at(v).back() - disk_2.at(v).front());
      }
    deallog << scheme << ": impulse / momentum change of disk 2 = "
            << impulse[0] / change_2[0] << ", " << impulse[1] / change_2[1]
            << ", of disk 1 = " << -impulse[0] / change_1[0] << ", "
            << -impulse[1] / change_1[1] << std::endl;

    // The force acts from the output before the gap closes to the one
    // after it opens again (without the gap check, grid contact starts
    // when the two grains' points share nodes); the coordination number
    // is 1 exactly where a force acts.
    double       first = -1., last = -1., first_gap = 0., last_gap = 0.;
    unsigned int coordination_mismatch = 0;
    for (unsigned int k = 0; k < times.size(); ++k)
      {
        double force = 0.;
        for (unsigned int r = 0; r < contacts.at("time").size(); ++r)
          if (contacts.at("time")[r] == times[k])
            force = contacts.at("normal_force")[r];
        // Gap between the surfaces at the start of the interval, in cells.
        const unsigned int j = (k > 0 ? k - 1 : 0);
        const double       gap =
          (std::hypot(disk_2.at("centre_x")[j] - disk_1.at("centre_x")[j],
                      disk_2.at("centre_y")[j] - disk_1.at("centre_y")[j]) -
           0.4) /
          0.05;
        if (force > 1e-6 * peak)
          {
            if (first < 0.)
              {
                first     = times[k];
                first_gap = gap;
              }
            last     = times[k];
            last_gap = gap;
          }
        // (Only one pair: the largest force of the output is its own.)
        coordination_mismatch +=
          (disk_1.at("coordination_number")[k] != (force > 0. ? 1. : 0.));
      }
    deallog << scheme << ": force over the outputs from t = " << first
            << " (gap " << first_gap << " cells at the interval's start) to "
            << last << " (" << last_gap
            << " cells), zero before and after; coordination numbers that "
               "disagree: "
            << coordination_mismatch << std::endl;
  }



  void
  roll(const double mu)
  {
    const double       R = 0.1, angle = 20. * numbers::PI / 180.;
    std::ostringstream name, text;
    name << "incline_" << mu;
    text << std::setprecision(12) << "set Dimension = 2\n"
         << "subsection Background grid\n  set Upper corner = 1, 0.3\n"
         << "  set Number of cells = 80, 24\nend\n"
         << "subsection Physics\n  set Gravity = " << std::sin(angle) << ", "
         << -std::cos(angle) << "\nend\n"
         << "subsection Materials\n  subsection elastic\n    set Density = 1\n"
         << "    set Young's modulus = 1000\n    set Poisson's ratio = 0.3\n"
         << "  end\nend\n"
         << "subsection Grains\n  subsection Slab\n    set Shape = rectangle\n"
         << "    set Centre = 0.5, 0.025\n    set Size = 1, 0.05\n"
         << "    set Material = elastic\n    set Rigid = true\n"
         << "    set Prescribed velocity = 0; 0\n  end\n"
         << "  subsection Disk\n    set Shape = disk\n    set Centre = 0.2, "
         << 0.05 + R << "\n    set Radius = " << R
         << "\n    set Material = elastic\n  end\nend\n"
         << "subsection Contact\n  set Contact model = Coulomb friction\n"
         << "  set Friction coefficient = " << mu << "\nend\n"
         << "subsection Time stepping\n  set End time = 0.8\nend\n";
    run_case(name.str(), text.str());
    const auto contacts = read_csv("results-" + name.str() + "/contacts.csv");
    const auto disk =
      grain_rows(read_csv("results-" + name.str() + "/grains.csv"), 2);
    double mobilised = 0., share = 0., sliding = 0., pair = 0.;
    for (unsigned int r = 0; r < contacts.at("time").size(); ++r)
      {
        pair += contacts.at("tangential_force")[r] /
                (mu * contacts.at("normal_force")[r]);
        mobilised += contacts.at("mobilised_friction")[r];
        share += contacts.at("slip_share")[r];
        sliding += contacts.at("sliding")[r];
      }
    const unsigned int n  = contacts.at("time").size();
    const double       dx = disk.at("centre_x").back() - 0.2;
    deallog << "mu = " << mu << ": mean |F_t| / (mu F_n) " << pair / n
            << ", mean mobilised friction " << mobilised / n << ", slip share "
            << share / n << ", sliding in " << sliding / n
            << " of the outputs, -R theta / dx = "
            << -R * disk.at("rotation_z").back() / dx
            << ", coordination number " << disk.at("coordination_number").back()
            << std::endl;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::setprecision(4);
  collide("explicit");
  collide("implicit");
  roll(0.3);
  roll(0.05);
}
