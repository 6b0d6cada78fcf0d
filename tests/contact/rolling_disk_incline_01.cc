// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A disk on a rough incline: the floor y = 0 is a wall with Coulomb
// friction mu and gravity is tilted by 20 degrees. A rigid disk rolls
// without slipping, with the centre acceleration a = (2/3) g sin(20 deg),
// if mu > tan(20 deg) / 3 = 0.121, and slides with a = g (sin - mu cos)
// below. The elastic disk (R = 0.1 = 8 h and 16 h, rho = 1, E = 1000,
// nu = 0.3, uGIMP, explicit at CFL 0.25) starts at rest touching the
// floor, as in the analytic problem: dropped from h/8 above it, the disk
// (read from its shape, `Contact/Shape gap`) bounces elastically and
// slips while in the air (slip 0.10 at R = 8 h). Printed at t = 0.8: the
// centre's mean acceleration 2 dx / t^2 against the rigid-disk value, and the
// slip 1 - R |theta| / dx of the rotation angle theta of the material points
// about the centre of mass against the centre's displacement dx. Without the
// gap check the friction wall acts on the whole first cell layer and the disk
// hardly turns; with it the disk rolls (mu = 0.3: acceleration within 3 %, slip
// under 10 % at R = 8 h and under 5 % at R = 16 h) or slides and spins up (mu =
// 0.05; the rigid disk's slip is 1 - 2 mu cos / (sin - mu cos) = 0.681). With
// arguments n_cells (R = n_cells h / 10), mu and 0 or 1 (gap check) that case
// alone: at R = 32 h the rolling disk's slip is 2.2 %. Since the wall leaves
// to a node the normal speed that the disk's rotation gives it
// (GapEstimator::wall_turning_speed()), the rolling slip fell from 4.8 %,
// 4.2 % and 3.7 % at R = 8, 16 and 32 h, and the sliding disk turns more
// (slip 0.641 and 0.648 at R = 8 and 16 h against 0.666 and 0.669).

#include <grainmpm/time_integration/explicit_leapfrog.h>

#include <map>

#include "../tests.h"

#include "../implicit_fixture.h"

using namespace grainmpm;

void
roll(const unsigned int n_cells, const double mu, const bool gap_check)
{
  const double       h     = 1. / n_cells;
  const double       R     = 0.1;
  const double       angle = 20. * numbers::PI / 180.;
  const double       g     = 1.;
  std::ostringstream text;
  text << std::setprecision(12) << "set Dimension = 2\n"
       << "subsection Background grid\n  set Upper corner = 1, 0.25\n"
       << "  set Number of cells = " << n_cells << ", " << n_cells / 4
       << "\n  set Boundary conditions = y-: friction " << mu << "\nend\n"
       << "subsection Physics\n  set Gravity = " << g * std::sin(angle) << ", "
       << -g * std::cos(angle) << "\nend\n"
       << "subsection Materials\n  subsection elastic\n    set Density = 1\n"
       << "    set Young's modulus = 1000\n    set Poisson's ratio = 0.3\n"
       << "  end\nend\n"
       << "subsection Grains\n  subsection Grain 1\n    set Shape = disk\n"
       << "    set Centre = 0.2, " << R << "\n    set Radius = " << R
       << "\n    set Material = elastic\n  end\nend\n"
       << "subsection Material points\n  set Shape functions = uGIMP\nend\n"
       // The gap check is the default: only its absence is set.
       << (gap_check ? "" :
                       "subsection Contact\n  set Gap check = false\nend\n");
  ImplicitFixture<2>  fixture(text.str(), "rolling_disk_incline_01");
  ExplicitLeapfrog<2> stepper(fixture.parameters,
                              *fixture.grid,
                              fixture.grains,
                              fixture.materials);

  using Layout = MaterialPointLayout<2>;
  // Centre of mass and its velocity.
  const auto centre_of_mass = [&]() {
    double       mass = 0.;
    Tensor<1, 2> first_moment, momentum;
    for (const auto &particle : *fixture.particle_handler)
      {
        const auto   properties = particle.get_properties();
        const double m          = properties[Layout::mass];
        mass += m;
        first_moment += m * Tensor<1, 2>(particle.get_location());
        momentum += m * Layout::get_velocity(properties);
      }
    return std::make_pair(Point<2>(first_moment / mass), momentum / mass);
  };

  const double wave_speed =
    std::sqrt(1000. * (1. - 0.3) / ((1. + 0.3) * (1. - 2. * 0.3)));
  const double       start_time = 0., end_time = 0.8;
  const unsigned int n_steps =
    static_cast<unsigned int>(std::ceil(end_time / (0.25 * h / wave_speed)));
  const double dt      = end_time / n_steps;
  const auto   advance = [&](const unsigned int first, const unsigned int end) {
    for (unsigned int step = first; step < end; ++step)
      stepper.advance(*fixture.particle_handler, step * dt, dt);
  };
  const unsigned int start_step =
    static_cast<unsigned int>(std::round(start_time / dt));
  advance(0, start_step);

  const auto [x0, v0] = centre_of_mass();
  std::map<types::particle_index, Tensor<1, 2>> initial;
  for (const auto &particle : *fixture.particle_handler)
    initial[particle.get_id()] = particle.get_location() - x0;
  advance(start_step, n_steps);

  // The rotation angle: the angle of the best rotation of the initial onto
  // the current positions about the centre of mass.
  const Point<2> x1   = centre_of_mass().first;
  double         sine = 0., cosine = 0.;
  for (const auto &particle : *fixture.particle_handler)
    {
      const double        m  = particle.get_properties()[Layout::mass];
      const Tensor<1, 2> &r0 = initial[particle.get_id()];
      const Tensor<1, 2>  r  = particle.get_location() - x1;
      sine += m * (r0[0] * r[1] - r0[1] * r[0]);
      cosine += m * (r0 * r);
    }
  const double theta    = std::atan2(sine, cosine);
  const double dx       = x1[0] - x0[0];
  const double duration = (n_steps - start_step) * dt;
  const double a        = 2. * (dx - v0[0] * duration) / (duration * duration);
  const double slip     = 1. - R * std::abs(theta) / dx;
  const bool   rolls    = mu > std::tan(angle) / 3.;
  const double expected = rolls ? 2. / 3. * g * std::sin(angle) :
                                  g * (std::sin(angle) - mu * std::cos(angle));

  deallog << std::fixed << std::setprecision(2) << "h = R/" << n_cells / 10
          << ", mu = " << mu << " (" << (rolls ? "rolls" : "slides")
          << "), gap check " << (gap_check ? "on" : "off")
          << ": a / a_rigid = " << std::setprecision(3) << a / expected
          << " (within 3 %: "
          << (std::abs(a / expected - 1.) < 0.03 ? "yes" : "no")
          << "), slip = " << std::setprecision(3) << slip;
  // Rolling: slip at most 10 % at R = 8 h, 5 % from R = 16 h.
  const double slip_bound = n_cells < 160 ? 0.10 : 0.05;
  if (rolls)
    deallog << " (< " << std::setprecision(2) << slip_bound << ": "
            << (std::abs(slip) < slip_bound ? "yes" : "no") << ")";
  else
    deallog << " (rigid disk "
            << 1. - 2. * mu * std::cos(angle) /
                      (std::sin(angle) - mu * std::cos(angle))
            << ")";
  deallog << std::defaultfloat << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  // With arguments n_cells, mu and 0 or 1 (gap check): that case alone.
  if (argc == 4)
    {
      roll(std::atoi(argv[1]), std::atof(argv[2]), std::atoi(argv[3]) != 0);
      return 0;
    }
  roll(80, 0.3, false);
  roll(80, 0.3, true);
  roll(160, 0.3, true);
  roll(80, 0.05, true);
}
