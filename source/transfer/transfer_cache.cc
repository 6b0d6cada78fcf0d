// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

namespace grainmpm
{
  template <int dim>
  void
  TransferCache<dim>::reinit(
    const BackgroundGrid<dim>             &grid,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<unsigned int>       &field_of_grain)
  {
    const std::size_t n = particle_handler.n_locally_owned_particles();
    nodes.resize(n * nodes_per_particle);
    shape_values.resize(n * nodes_per_particle);
    shape_gradients.resize(n * nodes_per_particle);
    fields.resize(n);
    slots.resize(n * nodes_per_particle);

    Tensor<1, dim> inverse_h;
    for (unsigned int d = 0; d < dim; ++d)
      inverse_h[d] = 1. / grid.cell_size()[d];

    // Loop over cells, then over the particles in each cell: the node table
    // entry is looked up once per cell.
    std::size_t p = 0;
    for_each_particle(
      grid, particle_handler, [&](const auto &cell, const auto &particle) {
        const unsigned int *cell_nodes =
          grid.cell_nodes(cell->active_cell_index());
        const Point<dim> xi = particle->get_reference_location();
        // Q1: S = prod_d N_d, N_d = xi_d (vertex bit 1) or 1 - xi_d.
        double one_d_values[dim][2];
        for (unsigned int d = 0; d < dim; ++d)
          {
            one_d_values[d][0] = 1. - xi[d];
            one_d_values[d][1] = xi[d];
          }
        for (unsigned int v = 0; v < nodes_per_particle; ++v)
          {
            double         value = 1.;
            Tensor<1, dim> gradient;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const unsigned int bit = (v >> d) & 1U;
                value *= one_d_values[d][bit];
                double derivative = (bit ? 1. : -1.) * inverse_h[d];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    derivative *= one_d_values[e][(v >> e) & 1U];
                gradient[d] = derivative;
              }
            nodes[p * nodes_per_particle + v]           = cell_nodes[v];
            shape_values[p * nodes_per_particle + v]    = value;
            shape_gradients[p * nodes_per_particle + v] = gradient;
          }
        fields[p] = field_of_grain[MaterialPointLayout<dim>::get_grain(
          particle->get_properties())];
        ++p;
      });
    AssertDimension(p, n);
  }



  template class TransferCache<2>;
  template class TransferCache<3>;
} // namespace grainmpm
