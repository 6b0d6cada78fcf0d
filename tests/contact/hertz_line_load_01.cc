// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Hertz line contact: an elastic disk (R = 0.25, E = 1000, nu = 0.3,
// rho = 1, plane strain) rests on a free-slip floor under gravity g = 60
// (load P = rho g pi R^2 per unit thickness); the implicit scheme with
// theta = 1 at CFL 4 damps the settling (to t = 2). In the settled state
// the floor's nodal reactions F_i give the load sum F_i and the contact
// half-width a = 2 sqrt(<x^2>), as for an elliptical pressure p0 sqrt(1 -
// x^2 / a^2), whose <x^2> = a^2 / 4 (less the hats' own h^2 / 6). Hertz for
// a cylinder on a rigid flat: a = sqrt(4 P R / (pi E*)), E* = E / (1 -
// nu^2), here a = 0.234 R (peak pressure p0 = E* a / (2 R) = 0.13 E).
//
// The load is chosen so that the indentation scale a^2 / R = 0.055 R is
// larger than the steps of the material points' surface (half a cell at 2
// points per cell) from R / h = 8 on: at g = 25 (a = 0.151 R, a^2 / R =
// 0.023 R = 0.18 h at R / h = 8) the lowest row of points of the disk is a
// flat facet wider than the Hertz patch, the disk bears on it like a flat
// punch, and the half-width follows the facet, not Hertz.
//
// With the gap check the half-width is within one cell of Hertz and
// converges under refinement (a / R = 0.184, 0.220, 0.229 at R / h = 8,
// 16, 32; R / h = 32 with arguments "32 1 4 2", about 5 minutes). Without
// it the floor holds every node where the disk has mass in the first cell
// layer: a flat patch 1.8 and 2.5 cells wider than Hertz at R / h = 8 and
// 16 that shrinks only as the first cell layer does.

#include "../tests.h"

#include "../implicit_fixture.h"

using namespace grainmpm;

// Settle the disk and print the load and the half-width; returns the
// half-width's error (a - a_Hertz) / R.
double
press(const unsigned int radius_in_cells,
      const double       g,
      const bool         gap_check,
      const double       cfl      = 4.,
      const double       end_time = 2.)
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
       // The gap check is the default: only its absence is set.
       << (gap_check ? "" :
                       "subsection Contact\n  set Gap check = false\nend\n")
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
      AssertThrow(result.solver.converged, ExcMessage("Newton failed"));
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
          << ", (a - a_Hertz) / h = " << (a - a_hertz) / h
          << " (within one cell: " << (std::abs(a - a_hertz) < h ? "yes" : "no")
          << ")" << std::defaultfloat << std::endl;
  return (a - a_hertz) / R;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  // With arguments R/h, 0 or 1 (gap check), the CFL number and the end
  // time: that case alone, for the refinement study of doc/validation.md.
  const double g = 60.;
  if (argc == 5)
    press(std::atoi(argv[1]),
          g,
          std::atoi(argv[2]) != 0,
          std::atof(argv[3]),
          std::atof(argv[4]));
  else
    {
      press(8, g, false);
      press(16, g, false);
      const double coarse = press(8, g, true);
      const double fine   = press(16, g, true);
      deallog << "gap check: |a - a_Hertz| / R falls from R / h = 8 to 16: "
              << (std::abs(fine) < std::abs(coarse) ? "yes" : "no")
              << std::endl;
    }
}
