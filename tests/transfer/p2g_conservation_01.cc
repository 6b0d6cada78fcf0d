// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// GrainFieldLayout: the (node, field) slots of two grains are exactly the
// pairs the particles touch, contact nodes are the nodes shared by both,
// every (particle, vertex) pair points to a slot of its own node and field,
// and the P2G sums over the slots conserve mass and momentum per field.

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/particles/particle_handler.h>

#include <set>

#include "../tests.h"

using namespace grainmpm;

// A fixed linear congruential generator: uniform numbers in [0, 1).
double
uniform()
{
  static unsigned long long state = 12345;
  return uniform_random(state);
}



template <int dim>
void
check_layout(const BackgroundGrid<dim>             &grid,
             const Particles::ParticleHandler<dim> &particle_handler,
             const std::vector<unsigned int>       &field_of_grain)
{
  using Layout = MaterialPointLayout<dim>;

  deallog << "field of grain = (" << field_of_grain[0] << ", "
          << field_of_grain[1] << ")" << std::endl;

  TransferCache<dim> cache;
  cache.reinit(grid, particle_handler, field_of_grain);
  GrainFieldLayout<dim> layout;
  layout.reinit(cache, grid);

  // Particle data in cache order, read from the particles themselves.
  std::vector<unsigned int>   grains;
  std::vector<double>         masses;
  std::vector<Tensor<1, dim>> velocities;
  for_each_particle(grid,
                    particle_handler,
                    [&](const auto &, const auto &particle) {
                      const auto properties = particle->get_properties();
                      grains.push_back(Layout::get_grain(properties));
                      masses.push_back(properties[Layout::mass]);
                      velocities.push_back(Layout::get_velocity(properties));
                    });
  AssertDimension(grains.size(), cache.n_particles());

  // The expected slots: distinct (node, field) pairs touched.
  std::set<std::pair<unsigned int, unsigned int>> pairs;
  for (unsigned int p = 0; p < cache.n_particles(); ++p)
    for (unsigned int v = cache.first_entry[p]; v < cache.first_entry[p + 1];
         ++v)
      pairs.insert({cache.nodes[v], field_of_grain[grains[p]]});
  std::vector<unsigned int> fields_at_node(grid.n_nodes(), 0);
  for (const auto &pair : pairs)
    ++fields_at_node[pair.first];
  unsigned int expected_contact_nodes = 0;
  for (const unsigned int n : fields_at_node)
    if (n > 1)
      ++expected_contact_nodes;

  deallog << "slots: " << layout.n_slots() << " (expected " << pairs.size()
          << ")" << std::endl;
  deallog << "contact nodes: " << layout.contact_nodes().size() << " (expected "
          << expected_contact_nodes << ")" << std::endl;

  // Every slot is one of the pairs, every node's slots are its own.
  unsigned int bad_slots = 0;
  for (unsigned int node = 0; node < layout.n_nodes(); ++node)
    for (unsigned int s = layout.node_slots_begin(node);
         s < layout.node_slots_end(node);
         ++s)
      if (layout.node(s) != node || pairs.count({node, layout.field(s)}) == 0)
        ++bad_slots;
  for (const unsigned int node : layout.contact_nodes())
    if (fields_at_node[node] < 2)
      ++bad_slots;
  deallog << "slots not matching a touched (node, field) pair: " << bad_slots
          << std::endl;

  // Every (particle, vertex) pair points to the slot of its node and field.
  unsigned int bad_pairs = 0;
  for (unsigned int p = 0; p < cache.n_particles(); ++p)
    for (unsigned int v = cache.first_entry[p]; v < cache.first_entry[p + 1];
         ++v)
      {
        const unsigned int s = cache.slots[v];
        if (s >= layout.n_slots() || layout.node(s) != cache.nodes[v] ||
            layout.field(s) != field_of_grain[grains[p]])
          ++bad_pairs;
      }
  deallog << "(particle, vertex) pairs with a wrong slot: " << bad_pairs
          << std::endl;

  // P2G over the slots.
  LinearAlgebra::distributed::Vector<double> slot_mass, slot_momentum;
  layout.reinit_vector(slot_mass, 1);
  layout.reinit_vector(slot_momentum, dim);
  for (unsigned int p = 0; p < cache.n_particles(); ++p)
    for (unsigned int v = cache.first_entry[p]; v < cache.first_entry[p + 1];
         ++v)
      {
        const unsigned int s      = cache.slots[v];
        const double       weight = masses[p] * cache.shape_values[v];
        slot_mass.local_element(s) += weight;
        for (unsigned int d = 0; d < dim; ++d)
          slot_momentum.local_element(s * dim + d) += weight * velocities[p][d];
      }

  const unsigned int n_fields =
    1 + *std::max_element(field_of_grain.begin(), field_of_grain.end());
  std::vector<double>         grid_mass(n_fields), particle_mass(n_fields);
  std::vector<Tensor<1, dim>> grid_momentum(n_fields),
    particle_momentum(n_fields);
  double momentum_scale = 0.;
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    {
      grid_mass[layout.field(s)] += slot_mass.local_element(s);
      for (unsigned int d = 0; d < dim; ++d)
        grid_momentum[layout.field(s)][d] +=
          slot_momentum.local_element(s * dim + d);
    }
  for (unsigned int p = 0; p < grains.size(); ++p)
    {
      particle_mass[field_of_grain[grains[p]]] += masses[p];
      particle_momentum[field_of_grain[grains[p]]] += masses[p] * velocities[p];
      momentum_scale += masses[p] * velocities[p].norm();
    }
  double         total_grid_mass = 0., total_particle_mass = 0.;
  Tensor<1, dim> total_grid_momentum, total_particle_momentum;
  for (unsigned int f = 0; f < n_fields; ++f)
    {
      deallog << "field " << f << ": grid mass / particle mass = "
              << grid_mass[f] / particle_mass[f]
              << ", |grid - particle momentum| / scale = "
              << filter_out_small_numbers(
                   (grid_momentum[f] - particle_momentum[f]).norm() /
                   momentum_scale)
              << std::endl;
      total_grid_mass += grid_mass[f];
      total_particle_mass += particle_mass[f];
      total_grid_momentum += grid_momentum[f];
      total_particle_momentum += particle_momentum[f];
    }
  deallog << "total: grid mass / particle mass = "
          << total_grid_mass / total_particle_mass
          << ", |grid - particle momentum| / scale = "
          << filter_out_small_numbers(
               (total_grid_momentum - total_particle_momentum).norm() /
               momentum_scale)
          << std::endl;
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  using Layout = MaterialPointLayout<dim>;

  BackgroundGridParameters<dim> parameters;
  parameters.n_cells = std::vector<unsigned int>(dim, 4);
  parameters.check();
  BackgroundGrid<dim> grid(parameters, MPI_COMM_WORLD);

  Particles::ParticleHandler<dim> particle_handler(grid.get_triangulation(),
                                                   grid.get_mapping(),
                                                   Layout::n_properties);

  // Grain 0 in x < 0.45, grain 1 in x > 0.55, y (and z) in (0.3, 0.9):
  // the grains share the nodes at x = 0.5 of the rows they both reach.
  const unsigned int  n_per_grain = (dim == 2 ? 20 : 40);
  std::vector<double> properties(Layout::n_properties, 0.);
  for (unsigned int g = 0; g < 2; ++g)
    for (unsigned int i = 0; i < n_per_grain; ++i)
      {
        Point<dim> x;
        x[0] = (g == 0 ? 0.05 : 0.55) + 0.4 * uniform();
        for (unsigned int d = 1; d < dim; ++d)
          x[d] = 0.3 + 0.6 * uniform();
        std::fill(properties.begin(), properties.end(), 0.);
        properties[Layout::mass]  = 0.5 + uniform();
        properties[Layout::grain] = g;
        for (unsigned int d = 0; d < dim; ++d)
          properties[Layout::velocity + d] = 2. * uniform() - 1.;
        const auto cell_and_reference =
          GridTools::find_active_cell_around_point(grid.get_mapping(),
                                                   grid.get_triangulation(),
                                                   x);
        particle_handler.insert_particle(x,
                                         cell_and_reference.second,
                                         g * n_per_grain + i,
                                         cell_and_reference.first,
                                         make_array_view(properties));
      }
  particle_handler.update_cached_numbers();

  check_layout(grid, particle_handler, {0, 1});
  check_layout(grid, particle_handler, {1, 0});
  check_layout(grid, particle_handler, {0, 0});
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
