// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// TransferCache: the Q1 shape values of every particle sum to one, their
// gradients to zero, values and gradients match the tensor-product formula
// at the cached node positions, and the gradients match central differences
// of the cached values.

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/particles/particle_handler.h>

#include "../tests.h"

#include "anisotropic_box.h"

using namespace grainmpm;

template <int dim>
void
insert(const BackgroundGrid<dim>       &grid,
       Particles::ParticleHandler<dim> &particle_handler,
       const Point<dim>                &position,
       const types::particle_index      id)
{
  const auto cell_and_reference =
    GridTools::find_active_cell_around_point(grid.get_mapping(),
                                             grid.get_triangulation(),
                                             position);
  std::vector<double> properties(MaterialPointLayout<dim>::n_properties, 0.);
  properties[MaterialPointLayout<dim>::mass]  = 1.;
  properties[MaterialPointLayout<dim>::grain] = 0.;
  particle_handler.insert_particle(position,
                                   cell_and_reference.second,
                                   id,
                                   cell_and_reference.first,
                                   make_array_view(properties));
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;

  // An anisotropic box with unequal cells: h = (0.5, 0.5, 0.25).
  const BackgroundGridParameters<dim> parameters =
    anisotropic_box_parameters<dim>();
  BackgroundGrid<dim> grid(parameters, MPI_COMM_WORLD);

  Particles::ParticleHandler<dim> particle_handler(
    grid.get_triangulation(),
    grid.get_mapping(),
    MaterialPointLayout<dim>::n_properties);

  // A few particles at generic positions, one on a cell face, one at a
  // grid node; then a stencil x0, x0 +- eps e_d inside one cell for the
  // finite differences.
  std::vector<Point<dim>> positions =
    spread_positions(parameters, 4, 0.1, 0.2, 0.037);
  {
    Point<dim> x = positions[0];
    x[0]         = 0.; // on the face between two cells
    positions.push_back(x);
    Point<dim> node;
    for (unsigned int d = 0; d < dim; ++d)
      node[d] = parameters.lower_corner[d] + 2. * grid.cell_size()[d];
    positions.push_back(node);
  }
  const unsigned int n_plain = positions.size();
  Point<dim>         x0;
  for (unsigned int d = 0; d < dim; ++d)
    x0[d] = parameters.lower_corner[d] + (1.3 + 0.1 * d) * grid.cell_size()[d];
  const double eps = 1e-3 * grid.minimum_cell_size();
  add_difference_stencil(positions, x0, eps);

  for (unsigned int i = 0; i < positions.size(); ++i)
    insert(grid, particle_handler, positions[i], i);
  particle_handler.update_cached_numbers();

  TransferCache<dim> cache;
  cache.reinit(grid, particle_handler, {0});
  AssertDimension(cache.n_particles(), positions.size());

  constexpr unsigned int n_v = 1U << dim;

  // Cache position p -> particle id (the cache follows for_each_particle).
  std::vector<types::particle_index> id_of(cache.n_particles());
  std::vector<unsigned int>          p_of_id(positions.size());
  {
    unsigned int p = 0;
    for_each_particle(grid,
                      particle_handler,
                      [&](const auto &, const auto &particle) {
                        id_of[p]                    = particle->get_id();
                        p_of_id[particle->get_id()] = p;
                        ++p;
                      });
  }

  // Partition of unity, and agreement with prod_d (1 - |x_d - X_d| / h_d)
  // evaluated at the positions of the cached nodes.
  double max_formula_error = 0.;
  for (unsigned int i = 0; i < n_plain; ++i)
    {
      const unsigned int p   = p_of_id[i];
      double             sum = 0.;
      Tensor<1, dim>     gradient_sum;
      AssertDimension(cache.first_entry[p + 1] - cache.first_entry[p], n_v);
      for (unsigned int v = 0; v < n_v; ++v)
        {
          const double value = cache.shape_values[p * n_v + v];
          sum += value;
          gradient_sum += cache.shape_gradients[p * n_v + v];

          const Point<dim> &node = grid.node_position(cache.nodes[p * n_v + v]);
          double            formula = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            formula *= std::max(0.,
                                1. - std::abs(positions[i][d] - node[d]) /
                                       grid.cell_size()[d]);
          max_formula_error =
            std::max(max_formula_error, std::abs(value - formula));
        }
      deallog << "particle " << i << ": sum S = " << sum
              << ", |sum grad S| * h = "
              << filter_out_small_numbers(gradient_sum.norm() *
                                          grid.minimum_cell_size())
              << std::endl;
    }
  deallog << "max |S - Q1 formula at node positions| = "
          << filter_out_small_numbers(max_formula_error) << std::endl;

  // Gradients of the stencil centre against central differences of the
  // cached values (exact for Q1 up to round-off, since S is linear in each
  // coordinate).
  const unsigned int p0             = p_of_id[n_plain];
  double             max_error      = 0.;
  double             gradient_scale = 0.;
  for (unsigned int v = 0; v < n_v; ++v)
    {
      Tensor<1, dim> difference_quotient;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const unsigned int minus = p_of_id[n_plain + 1 + 2 * d];
          const unsigned int plus  = p_of_id[n_plain + 2 + 2 * d];
          AssertThrow(cache.nodes[minus * n_v + v] ==
                          cache.nodes[p0 * n_v + v] &&
                        cache.nodes[plus * n_v + v] ==
                          cache.nodes[p0 * n_v + v],
                      ExcMessage("stencil left the cell"));
          difference_quotient[d] = (cache.shape_values[plus * n_v + v] -
                                    cache.shape_values[minus * n_v + v]) /
                                   (2. * eps);
        }
      max_error = std::max(
        max_error,
        (difference_quotient - cache.shape_gradients[p0 * n_v + v]).norm());
      gradient_scale =
        std::max(gradient_scale, cache.shape_gradients[p0 * n_v + v].norm());
    }
  deallog << "max |grad S - FD(S)| / max |grad S| = "
          << filter_out_small_numbers(max_error / gradient_scale, 1e-8)
          << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
