// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Mass scaling (Time stepping/Mass scaling) on slow loading, explicit:
// - a disk (R = 0.25, 8 cells) compressed by a rigid platen at
//   V/c = 1e-4: with alpha = 100 the run takes a tenth of the steps and
//   the mean platen force over the last quarter of the travel is that of
//   the unscaled run within 3 % (measured: 1 %); the inertial number
//   written in walls.csv agrees with (V / H) d / sqrt(P / rho) estimated
//   from the disk's size and the written force within 10 % (measured:
//   1.3e-3, 1 %), and grows by sqrt(alpha) with the scaled density;
// - the same disk resting on the floor under gravity: the floor takes the
//   true weight rho pi R^2 g with and without scaling, as gravity is
//   divided by alpha: its mean force over t in (0.5, 2], less the disk's
//   momentum change over that time divided by it, is the weight within 2 %
//   (measured +0.96 % at alpha = 1: the points cover 0.96 % more than
//   pi R^2).

#include <cmath>

#include "../tests.h"

#include "../energy_csv.h"

using namespace grainmpm;

namespace
{
  /** The case text: the shipped one-disk compression, explicit. */
  std::string
  disk_case(const double alpha, const std::string &extra)
  {
    std::ostringstream text;
    text << "include " GRAINMPM_SOURCE_DIR
            "/prm/slow_compression_one_disk.prm\n"
         << "subsection Background grid\n  set Number of cells = 32, 32\n"
         << "end\nsubsection Time stepping\n"
         << "  set Scheme = explicit leapfrog\n  set Stress update = USL\n"
         << "  set Time step = 0\n  set CFL number = 0.25\n"
         << "  set Mass scaling = " << alpha << "\nend\n"
         << extra;
    return text.str();
  }



  /**
   * The time average of the column @p name of @p walls over the steps
   * that end in (from, to].
   */
  double
  mean_over(const std::map<std::string, std::vector<double>> &walls,
            const std::string                                &name,
            const double                                      from,
            const double                                      to)
  {
    const auto &times  = walls.at("time");
    const auto &steps  = walls.at("dt");
    const auto &values = walls.at(name);
    double      sum = 0., duration = 0.;
    for (unsigned int i = 0; i < times.size(); ++i)
      if (times[i] > from && times[i] <= to)
        {
          sum += values[i] * steps[i];
          duration += steps[i];
        }
    return duration > 0. ? sum / duration : 0.;
  }



  struct Compression
  {
    double steps, force, inertial_number;
  };



  Compression
  compress(const double alpha)
  {
    const std::string name = "compress_" + std::to_string(int(alpha));
    run_case(name,
             disk_case(alpha,
                       "subsection Grains\n  subsection Platen\n"
                       "    set Prescribed velocity = 0; -0.0037\n"
                       "  end\nend\nsubsection Time stepping\n"
                       "  set End time = 2\nend\n"));
    const auto walls = read_csv("results-" + name + "/walls.csv");
    // The platen is grain 2; the force the disk exerts on it is upwards.
    return {static_cast<double>(walls.at("time").size()),
            mean_over(walls, "grain_2_force_y", 1.5, 2.),
            mean_over(walls, "grain_2_inertial_number", 1.5, 2.)};
  }



  double
  floor_force(const double alpha)
  {
    const std::string name = "rest_" + std::to_string(int(alpha));
    const auto        energy =
      run_case(name,
               disk_case(alpha,
                         "subsection Physics\n  set Gravity = 0, -1\nend\n"
                         "subsection Grains\n  subsection Platen\n"
                         "    set Centre = 0.5, 0.9\n"
                         "    set Prescribed velocity = 0; 0\n"
                         "  end\nend\nsubsection Time stepping\n"
                         "  set End time = 2\nend\n"));
    const auto walls = read_csv("results-" + name + "/walls.csv");
    // After the first half time unit: the load of gravity switched on at
    // t = 0 makes the disk oscillate, 10 times slower with alpha = 100.
    // The floor's mean force over (0.5, 2] is the weight plus the disk's
    // momentum change over that time (the oscillation does not end at a
    // whole period): subtract it.
    const auto  &times    = energy.at("time");
    const auto  &momentum = energy.at("momentum_y");
    unsigned int start    = 0;
    while (start + 1 < times.size() && times[start + 1] <= 0.5)
      ++start;
    return mean_over(walls, "wall_y-_force_y", 0.5, 2.) +
           (momentum.back() - momentum[start]) / (times.back() - times[start]);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const auto yes = [](const bool b) { return b ? "yes" : "no"; };

  const Compression plain  = compress(1.);
  const Compression scaled = compress(100.);
  deallog << "steps with alpha = 100 at most 0.11 of those without: "
          << yes(scaled.steps <= 0.11 * plain.steps) << std::endl;
  deallog << "mean platen force over the last quarter within 3 %: "
          << yes(std::abs(scaled.force / plain.force - 1.) < 0.03) << std::endl;
  // V = 0.0037, H ~ 0.5 (the disk), d = 0.5, rho = 1, P = F / 0.5.
  const double estimate =
    0.0037 / 0.5 * 0.5 / std::sqrt(std::abs(plain.force) / 0.5);
  deallog << "inertial number within 10 % of the estimate: "
          << yes(std::abs(plain.inertial_number / estimate - 1.) < 0.1)
          << ", grows with sqrt(alpha) (within 5 %): "
          << yes(std::abs(scaled.inertial_number / plain.inertial_number / 10. -
                          1.) < 0.05)
          << std::endl;

  // The weight of the disk per unit thickness, pushing down on the floor.
  const double weight = numbers::PI * 0.25 * 0.25;
  deallog << "floor force less the rate of momentum change = true weight "
             "within 2 %, alpha = 1: "
          << yes(std::abs(-floor_force(1.) / weight - 1.) < 0.02)
          << ", alpha = 100: "
          << yes(std::abs(-floor_force(100.) / weight - 1.) < 0.02)
          << std::endl;
}
