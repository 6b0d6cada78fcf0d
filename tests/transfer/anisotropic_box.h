// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The grid of the shape-function tests: an anisotropic box with unequal
// cells, h = (0.5, 0.5, 0.25).

#ifndef grainmpm_tests_transfer_anisotropic_box_h
#define grainmpm_tests_transfer_anisotropic_box_h

#include <grainmpm/base/parameters.h>

#include <deal.II/base/point.h>

#include <vector>

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



/**
 * @p n generic positions spread along the diagonal of the box of
 * @p parameters: fraction first + step k + skew (d + 1) of the box along
 * axis d for the k-th.
 */
template <int dim>
std::vector<dealii::Point<dim>>
spread_positions(const grainmpm::BackgroundGridParameters<dim> &parameters,
                 const unsigned int                             n,
                 const double                                   first,
                 const double                                   step,
                 const double                                   skew)
{
  std::vector<dealii::Point<dim>> positions;
  for (unsigned int k = 0; k < n; ++k)
    {
      dealii::Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = parameters.lower_corner[d] +
               (parameters.upper_corner[d] - parameters.lower_corner[d]) *
                 (first + step * k + skew * (d + 1));
      positions.push_back(x);
    }
  return positions;
}



/**
 * Append the central-difference stencil x0, x0 - eps e_0, x0 + eps e_0,
 * x0 - eps e_1, ... to @p positions.
 */
template <int dim>
void
add_difference_stencil(std::vector<dealii::Point<dim>> &positions,
                       const dealii::Point<dim>        &x0,
                       const double                     eps)
{
  positions.push_back(x0);
  for (unsigned int d = 0; d < dim; ++d)
    for (const double sign : {-1., 1.})
      {
        dealii::Point<dim> x = x0;
        x[d] += sign * eps;
        positions.push_back(x);
      }
}

#endif
