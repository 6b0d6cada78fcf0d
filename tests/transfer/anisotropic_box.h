// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The grid of the shape-function tests: an anisotropic box with unequal
// cells, h = (0.5, 0.5, 0.25).

#ifndef grainmpm_tests_transfer_anisotropic_box_h
#define grainmpm_tests_transfer_anisotropic_box_h

#include <grainmpm/base/parameters.h>

template <int dim>
grainmpm::BackgroundGridParameters<dim>
anisotropic_box_parameters()
{
  grainmpm::BackgroundGridParameters<dim> parameters;
  for (unsigned int d = 0; d < dim; ++d)
    {
      parameters.lower_corner[d] = -1. + 0.5 * d;
      parameters.upper_corner[d] = 1. + 0.5 * d;
    }
  parameters.n_cells = {4, 4, 8};
  parameters.n_cells.resize(dim);
  parameters.check();
  return parameters;
}

#endif
