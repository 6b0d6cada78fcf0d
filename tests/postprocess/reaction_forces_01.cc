// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// walls.csv: the force the grains exert on the box faces and on rigid
// grains, in both schemes.
// - A disk (R = 0.19, rho = 1, E = 1000) dropped by 0.01 onto a free-slip
//   floor under g = 10: the floor carries its weight (implicit theta = 1
//   damps the settling). The explicit disk bounces elastically: its mean
//   floor force over [1, 2] is the weight plus its momentum change over
//   that time (4 % here), and the floor's impulse is printed against
//   both.
// - The same disk on a rigid slab, 0.1 off the slab's centre: the slab
//   carries the weight and the torque -0.1 W about its centre, with the
//   gap check (the default) and without it. With it the frictionless disk
//   rests on one node of the slab's face and stays at x = 0.6 only because
//   it takes the slab's normal there (with the mixed normal it drifted by
//   two cells and turned).
// - A disk flying at speed 1 into the x+ wall without gravity: the time
//   integral of the wall's force over the rebound equals the disk's
//   momentum change (the constraint impulses are the only external ones).

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

namespace
{
  const std::string common =
    "set Dimension = 2\n"
    "subsection Background grid\n  set Upper corner = 1, 1\n"
    "  set Number of cells = 20, 20\nend\n"
    "subsection Materials\n  subsection elastic\n    set Density = 1\n"
    "    set Young's modulus = 1000\n    set Poisson's ratio = 0.3\n"
    "  end\nend\n";

  std::string
  scheme(const bool implicit, const double end_time)
  {
    return "subsection Time stepping\n  set End time = " +
           std::to_string(end_time) +
           (implicit ? "\n  set Scheme = implicit theta\n  set Theta = 1\n"
                       "  set CFL number = 4\n" :
                       "\n  set Stress update = USL\n") +
           "end\n";
  }

  std::string
  disk(const std::string &name,
       const double       x,
       const double       y,
       const std::string &velocity = "0; 0")
  {
    return "subsection Grains\n  subsection " + name +
           "\n    set Shape = disk\n    set Centre = " + std::to_string(x) +
           ", " + std::to_string(y) +
           "\n    set Radius = 0.19\n    set Material = elastic\n"
           "    set Initial velocity = " +
           velocity + "\n  end\nend\n";
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::fixed << std::setprecision(4);

  for (const bool implicit : {true, false})
    {
      const std::string name =
        std::string("floor_") + (implicit ? "implicit" : "explicit");
      const auto energy =
        run_case(name,
                 common + "subsection Physics\n  set Gravity = 0, -10\nend\n" +
                   disk("Disk", 0.5, 0.2) + scheme(implicit, 2.));
      const auto   walls  = read_csv("results-" + name + "/walls.csv");
      const auto   grains = read_csv("results-" + name + "/grains.csv");
      const double weight = 10. * grains.at("mass").front();
      // The floor's impulse on the disk over the steps in [1, 2] against
      // the weight's and the disk's momentum change (row i of walls.csv
      // ends at row i + 1 of energy.csv).
      const auto  &times   = walls.at("time");
      const auto  &dt      = walls.at("dt");
      double       impulse = 0., duration = 0.;
      unsigned int first = times.size(), last = 0;
      for (unsigned int i = 0; i < times.size(); ++i)
        if (times[i] - dt[i] >= 1. - 1e-9 && times[i] <= 2. + 1e-9)
          {
            impulse -= walls.at("wall_y-_force_y")[i] * dt[i];
            duration += dt[i];
            first = std::min(first, i);
            last  = i;
          }
      const auto &py = energy.at("momentum_y");
      deallog << (implicit ? "implicit" : "explicit")
              << ": floor force / weight over t in [1, 2] = "
              << -time_mean(times, walls.at("wall_y-_force_y"), 1., 2.) / weight
              << ", side walls "
              << time_mean(times, walls.at("wall_x-_force_x"), 1., 2.) / weight
              << ", floor impulse / (weight x time + momentum change) = "
              << impulse / (weight * duration + py[last + 1] - py[first])
              << std::endl;
    }

  for (const bool gap_check : {true, false})
    {
      const std::string name = gap_check ? "slab" : "slab_no_gap_check";
      run_case(name,
               common + "subsection Physics\n  set Gravity = 0, -10\nend\n" +
                 "subsection Grains\n  subsection Slab\n"
                 "    set Shape = rectangle\n    set Centre = 0.5, 0.1\n"
                 "    set Size = 0.9, 0.1\n    set Material = elastic\n"
                 "    set Rigid = true\n    set Prescribed velocity = 0; 0\n"
                 "  end\nend\n" +
                 disk("Disk", 0.6, 0.35) + scheme(true, 2.) +
                 (gap_check ?
                    "" :
                    "subsection Contact\n  set Gap check = false\nend\n"));
      const auto   walls  = read_csv("results-" + name + "/walls.csv");
      const auto   grains = read_csv("results-" + name + "/grains.csv");
      const double weight = 10. * grains.at("mass")[1];
      const auto  &times  = walls.at("time");
      deallog << "rigid slab" << (gap_check ? "" : " (Gap check = false)")
              << ": centre x at the end " << grains.at("centre_x").back()
              << ", force_y / -weight = "
              << -time_mean(times, walls.at("grain_1_force_y"), 1., 2.) / weight
              << ", torque / (-0.1 weight) = "
              << -time_mean(times, walls.at("grain_1_torque_z"), 1., 2.) /
                   (0.1 * weight)
              << ", floor "
              << time_mean(times, walls.at("wall_y-_force_y"), 1., 2.)
              << std::endl;
    }

  for (const bool implicit : {true, false})
    {
      const std::string name =
        std::string("impact_") + (implicit ? "implicit" : "explicit");
      const auto   energy  = run_case(name,
                                   common + disk("Disk", 0.7, 0.5, "1; 0") +
                                     scheme(implicit, 0.3));
      const auto   walls   = read_csv("results-" + name + "/walls.csv");
      const auto  &px      = energy.at("momentum_x");
      const double change  = px.back() - px.front();
      double       impulse = 0.;
      for (unsigned int i = 0; i < walls.at("time").size(); ++i)
        impulse += walls.at("wall_x+_force_x")[i] * walls.at("dt")[i];
      deallog << (implicit ? "implicit" : "explicit")
              << ": momentum change / initial momentum = "
              << change / px.front()
              << ", wall impulse / -(momentum change) = " << impulse / -change
              << ", equal to 1e-5: "
              << (std::abs(impulse / -change - 1.) < 1e-5 ? "yes" : "no")
              << std::endl;
    }
}
