// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// walls.csv in 3D: the force the grains exert on the box faces and on a
// rigid grain, with their weights and momentum changes as the reference
// (reaction_forces_01 in 2D). On one and on two MPI ranks (the same output).
// - A sphere (R = 0.19, rho = 1, E = 1000) settled on a free-slip floor
//   z = 0 under g = 10 (implicit theta = 1, which damps the settling): the
//   floor carries its weight and the side walls nothing.
// - The same sphere on a rigid box slab, off the slab's centre by
//   (0.1, -0.05): the slab carries the weight W and the torque about its
//   centre r x F = (-r_y W, r_x W, 0), r from the slab's centre to the
//   contact point below the ball's centre (its mean over the window).
// - A sphere flying at speed 1 into the x+ wall without gravity: the time
//   integral of the wall's force over the rebound equals the sphere's
//   momentum change over the steps with a wall force (explicit and
//   implicit). Printed too: the change of the momentum after the contact,
//   where no wall acts. In the implicit run it is about 1e-5 of the
//   momentum: the slots lighter than 1e-6 of the largest point mass are
//   not unknowns of the Newton solve and only follow gravity, so the
//   internal forces on them are not applied (with 1e-9 instead, the drift
//   was 2e-9).
// The torque ratios are printed to three digits: one Newton iteration more
// or less (round-off near the tolerance) grows an implicit step of the
// settling ball differently on one and two ranks, and the time means then
// differ in the fourth digit.

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

namespace
{
  const std::string common =
    "set Dimension = 3\n"
    "subsection Background grid\n  set Upper corner = 1, 1, 1\n"
    "  set Number of cells = 12, 12, 12\nend\n"
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
  sphere(const std::string &name,
         const std::string &centre,
         const std::string &velocity = "0; 0; 0")
  {
    return "subsection Grains\n  subsection " + name +
           "\n    set Shape = sphere\n    set Centre = " + centre +
           "\n    set Radius = 0.19\n    set Material = elastic\n"
           "    set Initial velocity = " +
           velocity + "\n  end\nend\n";
  }

  const std::string gravity =
    "subsection Physics\n  set Gravity = 0, 0, -10\nend\n";
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  deallog << std::fixed << std::setprecision(4);

  {
    run_case<3>("floor",
                common + gravity + sphere("Ball", "0.5, 0.5, 0.2") +
                  scheme(true, 2.));
    const auto   walls  = read_csv("results-floor/walls.csv");
    const auto   grains = read_csv("results-floor/grains.csv");
    const double weight = 10. * grains.at("mass").front();
    const auto  &times  = walls.at("time");
    deallog << "floor: force / weight over t in [1, 2] = "
            << -time_mean(times, walls.at("wall_z-_force_z"), 1., 2.) / weight
            << ", side walls "
            << time_mean(times, walls.at("wall_x-_force_x"), 1., 2.) / weight
            << ", "
            << time_mean(times, walls.at("wall_y-_force_y"), 1., 2.) / weight
            << std::endl;
  }

  {
    run_case<3>("slab",
                common + gravity +
                  "subsection Grains\n  subsection Slab\n"
                  "    set Shape = box\n    set Centre = 0.5, 0.5, 0.1\n"
                  "    set Size = 0.9, 0.9, 0.1\n    set Material = elastic\n"
                  "    set Rigid = true\n"
                  "    set Prescribed velocity = 0; 0; 0\n  end\nend\n" +
                  sphere("Ball", "0.6, 0.45, 0.35") + scheme(true, 2.));
    const auto   walls  = read_csv("results-slab/walls.csv");
    const auto   grains = read_csv("results-slab/grains.csv");
    const double weight = 10. * grains.at("mass")[1];
    const auto  &times  = walls.at("time");
    // The ball's mean centre over the window gives the lever arm.
    const auto   ball      = grain_rows(grains, 2);
    double       centre[2] = {0., 0.};
    unsigned int n_rows    = 0;
    for (unsigned int i = 0; i < ball.at("time").size(); ++i)
      if (ball.at("time")[i] >= 1.)
        {
          centre[0] += ball.at("centre_x")[i];
          centre[1] += ball.at("centre_y")[i];
          ++n_rows;
        }
    const double arm_x = centre[0] / n_rows - 0.5;
    const double arm_y = centre[1] / n_rows - 0.5;
    deallog << "rigid slab: ball centre over t in [1, 2] (" << arm_x + 0.5
            << ", " << arm_y + 0.5 << "), force / (0, 0, -weight) = "
            << time_mean(times, walls.at("grain_1_force_x"), 1., 2.) / weight
            << ", "
            << time_mean(times, walls.at("grain_1_force_y"), 1., 2.) / weight
            << ", "
            << -time_mean(times, walls.at("grain_1_force_z"), 1., 2.) / weight
            << "; torque / (-arm_y W, arm_x W, W) = " << std::setprecision(3)
            << time_mean(times, walls.at("grain_1_torque_x"), 1., 2.) /
                 (-arm_y * weight)
            << ", "
            << time_mean(times, walls.at("grain_1_torque_y"), 1., 2.) /
                 (arm_x * weight)
            << ", "
            << time_mean(times, walls.at("grain_1_torque_z"), 1., 2.) / weight
            << "; floor " << std::setprecision(4)
            << time_mean(times, walls.at("wall_z-_force_z"), 1., 2.)
            << std::endl;
  }

  for (const bool implicit : {true, false})
    {
      const std::string name =
        std::string("impact_") + (implicit ? "implicit" : "explicit");
      const auto energy =
        run_case<3>(name,
                    common + sphere("Ball", "0.7, 0.5, 0.5", "1; 0; 0") +
                      scheme(implicit, 0.3));
      const auto  walls = read_csv("results-" + name + "/walls.csv");
      const auto &px    = energy.at("momentum_x");
      const auto &force = walls.at("wall_x+_force_x");
      // The steps with a wall force, first to last (walls.csv starts at
      // step 1, energy.csv at step 0: row i of walls.csv ends at row i + 1
      // of energy.csv).
      unsigned int first = force.size(), last = 0;
      for (unsigned int i = 0; i < force.size(); ++i)
        if (force[i] != 0.)
          {
            first = std::min(first, i);
            last  = i;
          }
      AssertThrow(first <= last, ExcMessage("The sphere never hit the wall."));
      double impulse = 0.;
      for (unsigned int i = first; i <= last; ++i)
        impulse += force[i] * walls.at("dt")[i];
      const double change = px[last + 1] - px[first];
      deallog << (implicit ? "implicit" : "explicit")
              << ": momentum change / initial momentum = "
              << change / px.front()
              << ", wall impulse / -(momentum change) = " << impulse / -change
              << ", equal to 1e-5: "
              << (std::abs(impulse / -change - 1.) < 1e-5 ? "yes" : "no")
              << ", change after the contact below 1e-4 of the momentum: "
              << (std::abs((px.back() - px[last + 1]) / px.front()) < 1e-4 ?
                    "yes" :
                    "no")
              << std::endl;
    }
}
