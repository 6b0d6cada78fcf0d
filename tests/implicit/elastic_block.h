// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The small contact-free elastic configuration of the Jacobian tests: a
// rectangular grain at rest, unstressed, in the middle of a 10 x 10 grid,
// plane strain, E = 1000, nu = 0.3, rho = 1 (c = 36.69), theta = 1/2 and
// dt = 2 h / c (CFL 2).

#ifndef grainmpm_tests_implicit_elastic_block_h
#define grainmpm_tests_implicit_elastic_block_h

#include <string>

#include "../tests.h"

#include "../implicit_fixture.h"

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



/**
 * Two grains of the material "elastic" on a 10 x 10 grid in frictional
 * contact (mu = 0.3), moving towards each other: a rectangle and a disk,
 * implicit at dt = 5.45e-3, and @p extra. They are 0.6 cells apart and
 * meet at the nodes their supports share: the contact status comes from the
 * velocities alone (`Gap check = false`), which gives the operators under
 * test an active set at the first step.
 */
inline std::string
two_grains_in_contact_parameters(const std::string &extra = "")
{
  return unit_square_and_material(10) + R"(
subsection Grains
  subsection Grain 1
    set Shape            = rectangle
    set Centre           = 0.3, 0.5
    set Size             = 0.3, 0.3
    set Material         = elastic
    set Initial velocity = 1; 0.5
  end
  subsection Grain 2
    set Shape            = disk
    set Centre           = 0.67, 0.52
    set Radius           = 0.16
    set Material         = elastic
    set Initial velocity = -1; -0.2
  end
end
subsection Contact
  set Contact model        = Coulomb friction
  set Friction coefficient = 0.3
  set Gap check            = false
end
subsection Time stepping
  set Scheme    = implicit theta
  set Time step = 5.45e-3
end
)" + extra;
}

/**
 * Move every point of @p fixture by a random amount of up to 1/8 cell per
 * axis, staying in its cell: off the regular arrangement, whose GIMP boxes
 * tile the cells exactly, a point's box reaches over a cell face and it
 * touches 3 nodes along that axis.
 */
inline void
jitter(grainmpm::ImplicitFixture<2> &fixture)
{
  unsigned long long state = 2026;
  const double       h     = fixture.grid->minimum_cell_size();
  for (auto &particle : *fixture.particle_handler)
    {
      const dealii::Tensor<1, 2> shift = 0.125 * h * random_vector<2>(state);
      particle.set_location(particle.get_location() + shift);
      particle.set_reference_location(particle.get_reference_location() +
                                      shift / h);
    }
}

#endif
