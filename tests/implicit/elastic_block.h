// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The small contact-free elastic configuration of the Jacobian tests: a
// rectangular grain at rest, unstressed, in the middle of a 10 x 10 grid,
// plane strain, E = 1000, nu = 0.3, rho = 1 (c = 36.69), theta = 1/2 and
// dt = 2 h / c (CFL 2).

#ifndef grainmpm_tests_implicit_elastic_block_h
#define grainmpm_tests_implicit_elastic_block_h

#include <string>

inline std::string
elastic_block_parameters(const std::string &extra = "")
{
  return R"(
set Dimension = 2
subsection Background grid
  set Lower corner        = 0, 0
  set Upper corner        = 1, 1
  set Number of cells     = 10, 10
  set Boundary conditions = x-: free slip, x+: free slip, y-: free slip, y+: free slip
end
subsection Materials
  subsection elastic
    set Density         = 1
    set Young's modulus = 1000
    set Poisson's ratio = 0.3
  end
end
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

#endif
