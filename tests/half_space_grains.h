// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Test fixture: two grains filling the background grid on either side of
// the plane x = x_s, with 2^dim points per cell at reference positions 1/4
// and 3/4.

#ifndef grainmpm_tests_half_space_grains_h
#define grainmpm_tests_half_space_grains_h

#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/material_point_layout.h>

#include <deal.II/particles/particle_handler.h>

#include <algorithm>
#include <vector>

/**
 * Insert grain 0 (mass 1 per point, velocity @p velocity_0) where x < x_s
 * and grain 1 (mass 3 per point, velocity @p velocity_1) where x > x_s.
 */
template <int dim>
void
insert_half_space_grains(const grainmpm::BackgroundGrid<dim>     &grid,
                         dealii::Particles::ParticleHandler<dim> &particles,
                         const double                             x_s,
                         const dealii::Tensor<1, dim>            &velocity_0,
                         const dealii::Tensor<1, dim>            &velocity_1)
{
  using Layout                    = grainmpm::MaterialPointLayout<dim>;
  const double                  h = grid.cell_size()[0];
  std::vector<double>           properties(Layout::n_properties, 0.);
  dealii::types::particle_index id = 0;
  for (const auto &cell : grid.get_triangulation().active_cell_iterators())
    for (unsigned int q = 0; q < (1U << dim); ++q)
      {
        dealii::Point<dim> reference, x;
        for (unsigned int d = 0; d < dim; ++d)
          {
            reference[d] = ((q >> d) & 1U) ? 0.75 : 0.25;
            x[d]         = cell->vertex(0)[d] + h * reference[d];
          }
        const unsigned int grain = (x[0] < x_s ? 0 : 1);
        std::fill(properties.begin(), properties.end(), 0.);
        properties[Layout::mass]  = (grain == 0 ? 1. : 3.);
        properties[Layout::grain] = grain;
        Layout::set_velocity(grain == 0 ? velocity_0 : velocity_1,
                             dealii::make_array_view(properties));
        particles.insert_particle(
          x, reference, id++, cell, dealii::make_array_view(properties));
      }
  particles.update_cached_numbers();
}

#endif
