// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Hertz line contact: an elastic disk (R = 0.25, E = 1000, nu = 0.3,
// rho = 1, plane strain) rests on a free-slip floor under gravity g = 25
// (load P = rho g pi R^2 per unit thickness); the implicit scheme with
// theta = 1 at CFL 10 damps the settling (to t = 0.5). In the settled state
// the floor's nodal reactions F_i give the load sum F_i and the contact
// half-width a = 2 sqrt(<x^2>), as for an elliptical pressure p0 sqrt(1 -
// x^2 / a^2), whose <x^2> = a^2 / 4 (less the hats' own h^2 / 6). Hertz for
// a cylinder on a rigid flat: a = sqrt(4 P R / (pi E*)), E* = E / (1 -
// nu^2), here a = 0.151 R.
//
// This test records a known shortfall of the contact law. Without the gap
// check the floor holds every node where the disk has mass in the first
// cell layer, and the patch is far wider than Hertz: a - a_Hertz = 2.3,
// 3.3 and 4.1 cells at R / h = 8, 16 and 32 (it shrinks in R only as the
// first cell layer does). With the gap check, estimated from the fill
// fractions, it is too narrow once the patch spans several cells: -0.1,
// -0.9 and -1.4 cells (R / h = 32 needs arguments "32 1 4 1.5": CFL 4 to
// t = 1.5, Newton fails at CFL 10). Neither converges to Hertz; the output
// changes when the contact law is improved.

#include "../tests.h"

#include "../implicit_fixture.h"

using namespace grainmpm;

void
press(const unsigned int radius_in_cells,
      const double       g,
      const bool         gap_check,
      const double       cfl      = 10.,
      const double       end_time = 0.5)
{
  const double       R = 0.25, E = 1000., nu = 0.3;
  const double       h       = R / radius_in_cells;
  const unsigned int n_cells = 2 * radius_in_cells + radius_in_cells / 2;
  const double       L       = n_cells * h;
  std::ostringstream text;
  text << std::setprecision(12) << "set Dimension = 2\n"
       << "subsection Background grid\n  set Upper corner = " << L << ", " << L
       << "\n  set Number of cells = " << n_cells << ", " << n_cells
       << "\n  set Boundary conditions = y-: free slip\nend\n"
       << "subsection Physics\n  set Gravity = 0, " << -g << "\nend\n"
       << "subsection Materials\n  subsection elastic\n    set Density = 1\n"
       << "    set Young's modulus = " << E
       << "\n    set Poisson's ratio = " << nu << "\n  end\nend\n"
       << "subsection Grains\n  subsection Grain 1\n    set Shape = disk\n"
       << "    set Centre = " << L / 2 << ", " << R + h / 8.
       << "\n    set Radius = " << R
       << "\n    set Material = elastic\n  end\nend\n"
       << "subsection Contact\n  set Gap check = "
       << (gap_check ? "true" : "false") << "\nend\n"
       << "subsection Time stepping\n  set Scheme = implicit theta\n"
       << "  set Theta = 1\nend\n";
  ImplicitFixture<2> fixture(text.str(), "hertz_line_load_01");

  const double wave_speed =
    std::sqrt(E * (1. - nu) / ((1. + nu) * (1. - 2. * nu)));
  const unsigned int n_steps =
    static_cast<unsigned int>(std::ceil(end_time / (cfl * h / wave_speed)));
  const double dt = end_time / n_steps;
  for (unsigned int step = 0; step < n_steps; ++step)
    {
      const auto result =
        fixture.stepper->advance(*fixture.particle_handler, step * dt, dt);
      AssertThrow(result.converged, ExcMessage("Newton failed"));
    }

  // The floor's reaction at its nodes in the settled state: the force
  // m_s (v^n - v*) / dt that stops the unconstrained end velocity v* of a
  // step from v^n.
  auto &residual =
    fixture.stepper->prepare(*fixture.particle_handler, end_time, dt);
  LinearAlgebra::distributed::Vector<double> velocities(
    fixture.stepper->get_old_velocities());
  LinearAlgebra::distributed::Vector<double> r(velocities);
  residual.evaluate(velocities, r, false, true);
  const auto &layout = fixture.stepper->get_layout();
  const auto &masses = fixture.stepper->get_grid_state().masses;
  double      load = 0., first = 0., second = 0.;
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    {
      const Point<2> &x = fixture.grid->node_position(layout.node(s));
      if (x[1] > 1e-9 * L)
        continue;
      const double f =
        masses.local_element(s) * r.local_element(2 * s + 1) / dt;
      load += f;
      first += f * x[0];
      second += f * x[0] * x[0];
    }
  const double centre = first / load;
  // Nodal forces F_i = int p N_i dx have the second moment int p (x^2 +
  // (x - x_j)(x_{j+1} - x)) dx: subtract the hats' mean excess h^2 / 6.
  const double a = 2. * std::sqrt(second / load - centre * centre - h * h / 6.);
  const double weight = g * numbers::PI * R * R;
  const double a_hertz =
    std::sqrt(4. * weight * R * (1. - nu * nu) / (numbers::PI * E));
  deallog << std::fixed << std::setprecision(3) << "R / h = " << radius_in_cells
          << ", gap check " << (gap_check ? "on" : "off")
          << ": P / weight = " << load / weight << ", a / R = " << a / R
          << ", Hertz " << a_hertz / R
          << ", (a - a_Hertz) / h = " << (a - a_hertz) / h << std::defaultfloat
          << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  // With arguments R/h, 0 or 1 (gap check), the CFL number and the end
  // time: that case alone, for the refinement study of doc/validation.md.
  if (argc == 5)
    press(std::atoi(argv[1]),
          25.,
          std::atoi(argv[2]) != 0,
          std::atof(argv[3]),
          std::atof(argv[4]));
  else
    for (const unsigned int radius_in_cells : {8, 16})
      for (const bool gap_check : {false, true})
        press(radius_in_cells, 25., gap_check);
}
