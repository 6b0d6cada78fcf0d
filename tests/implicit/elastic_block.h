// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The small contact-free elastic configuration of the Jacobian tests: a
// rectangular grain at rest, unstressed, in the middle of a 10 x 10 grid,
// plane strain, E = 1000, nu = 0.3, rho = 1 (c = 36.69), theta = 1/2 and
// dt = 2 h / c (CFL 2).

#ifndef grainmpm_tests_implicit_elastic_block_h
#define grainmpm_tests_implicit_elastic_block_h

#include <string>

/**
 * The common part of the implicit tests' parameter texts: 2D, the unit
 * square with @p n_cells^2 cells and free-slip faces, and the material
 * "elastic" (rho = 1, E = 1000, nu = 0.3, plane strain: c = 36.69).
 */
inline std::string
unit_square_and_material(const unsigned int n_cells)
{
  const std::string n = std::to_string(n_cells);
  return R"(
set Dimension = 2
subsection Background grid
  set Lower corner        = 0, 0
  set Upper corner        = 1, 1
  set Number of cells     = )" +
         n + ", " + n + R"(
  set Boundary conditions = x-: free slip, x+: free slip, y-: free slip, y+: free slip
end
subsection Materials
  subsection elastic
    set Density         = 1
    set Young's modulus = 1000
    set Poisson's ratio = 0.3
  end
end
)";
}



inline std::string
elastic_block_parameters(const std::string &extra = "")
{
  return unit_square_and_material(10) + R"(
subsection Grains
  subsection Grain 1
    set Shape    = rectangle
    set Centre   = 0.52, 0.47
    set Size     = 0.41, 0.33
    set Material = elastic
  end
end
subsection Material points
  set Particles per cell = 2
end
subsection Time stepping
  set Scheme    = implicit theta
  set Theta     = 0.5
  set Time step = 5.45e-3
end
)" + extra;
}

/** Plane strain Lame constants of the block. */
constexpr double block_lambda = 1000. * 0.3 / (1.3 * 0.4);
constexpr double block_mu     = 1000. / 2.6;

/**
 * The two disks of prm/two_disks_implicit.prm (the two-disk collision of
 * Sulsky, Zhou & Schreyer 1995):
 * rho = 1000 and the two grains, the second centred at (0.8,
 * @p grain_2_y) (0.8: head-on), approaching at (0.1, 0.1) each.
 */
inline std::string
two_disks_parameters(const std::string &grain_2_y = "0.8")
{
  return R"(
subsection Materials
  subsection elastic
    set Density = 1000
  end
end
subsection Grains
  subsection Grain 1
    set Shape            = disk
    set Centre           = 0.2, 0.2
    set Radius           = 0.2
    set Material         = elastic
    set Initial velocity = 0.1; 0.1
  end
  subsection Grain 2
    set Shape            = disk
    set Centre           = 0.8, )" +
         grain_2_y + R"(
    set Radius           = 0.2
    set Material         = elastic
    set Initial velocity = -0.1; -0.1
  end
end
)";
}



#endif
