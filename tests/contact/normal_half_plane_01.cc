// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Contact normals of a half-plane grain (doc/theory.md section 5.1): the
// mass gradient sum_p m_p grad S_ip of a grain filling x < x_s (x_s in the
// middle of a cell) points out of the grain (+x) at the nodes at and just
// outside its surface; with a second grain filling x > x_s,
// GrainContact::compute_normals gives unit normals n_a = e_x = -n_b.

#include <grainmpm/base/parameters.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/mpi.h>

#include <deal.II/particles/particle_handler.h>

#include "../tests.h"

#include "../half_space_grains.h"

using namespace grainmpm;

template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  using Layout     = MaterialPointLayout<dim>;
  using VectorType = LinearAlgebra::distributed::Vector<double>;

  // Unit box, h = 0.25; surface at x_s = 0.375, the middle of the second
  // column of cells.
  BackgroundGridParameters<dim> parameters;
  parameters.n_cells = std::vector<unsigned int>(dim, 4);
  parameters.check();
  BackgroundGrid<dim> grid(parameters, MPI_COMM_WORLD);
  const double        x_s = 0.375;

  // 2^dim regular points per cell everywhere: grain 0 (mass 1 per point)
  // where x < x_s, grain 1 (mass 3 per point) where x > x_s.
  Particles::ParticleHandler<dim> particle_handler(grid.get_triangulation(),
                                                   grid.get_mapping(),
                                                   Layout::n_properties);
  insert_half_space_grains(
    grid, particle_handler, x_s, Tensor<1, dim>(), Tensor<1, dim>());

  TransferCache<dim> cache;
  cache.reinit(grid, particle_handler, {0, 1});
  GrainFieldLayout<dim> layout;
  layout.reinit(cache, grid);

  std::vector<double> masses;
  for_each_particle(
    grid, particle_handler, [&](const auto &, const auto &particle) {
      masses.push_back(particle->get_properties()[Layout::mass]);
    });

  VectorType mass_gradients;
  layout.reinit_vector(mass_gradients, dim);
  for (unsigned int p = 0; p < cache.n_particles(); ++p)
    for (unsigned int v = cache.first_entry[p]; v < cache.first_entry[p + 1];
         ++v)
      for (unsigned int d = 0; d < dim; ++d)
        mass_gradients.local_element(cache.slots[v] * dim + d) +=
          masses[p] * cache.shape_gradients[v][d];

  auto slot_vector = [&](const VectorType &vector, const unsigned int s) {
    Tensor<1, dim> value;
    for (unsigned int d = 0; d < dim; ++d)
      value[d] = vector.local_element(s * dim + d);
    return value;
  };
  auto is_interior = [&](const unsigned int node) {
    return grid.node_faces(node) == 0;
  };

  // (1) The mass gradient of grain 0 alone, normalised, at the interior
  // nodes of the columns x = 0.25 (inside, nearest the surface) and
  // x = 0.5 (just outside): it must be +e_x. At x = 0 (the box face, also
  // a surface of the grain) it must be -e_x.
  for (const double x_node : {0., 0.25, 0.5})
    {
      double       min_nx = 2., max_length_error = 0.;
      unsigned int n = 0;
      for (unsigned int s = 0; s < layout.n_slots(); ++s)
        {
          const unsigned int node = layout.node(s);
          if (layout.field(s) != 0 ||
              std::abs(grid.node_position(node)[0] - x_node) > 1e-12)
            continue;
          bool interior_across = true;
          for (unsigned int d = 1; d < dim; ++d)
            if (grid.node_position(node)[d] < 1e-12 ||
                grid.node_position(node)[d] > 1. - 1e-12)
              interior_across = false;
          if (!interior_across)
            continue;
          const Tensor<1, dim> g      = slot_vector(mass_gradients, s);
          const Tensor<1, dim> normal = g / g.norm();
          const double         sign   = (x_node == 0. ? -1. : 1.);
          min_nx                      = std::min(min_nx, sign * normal[0]);
          max_length_error =
            std::max(max_length_error,
                     std::abs(g[0]) > 0 ?
                       std::abs(g.norm() / std::abs(g[0]) - 1) :
                       1.);
          ++n;
        }
      deallog << "grain 0 alone, nodes at x = " << x_node << " (" << n
              << "): min n . (" << (x_node == 0. ? "-" : "+")
              << "e_x) = " << min_nx << ", max |g| / |g_x| - 1 = "
              << filter_out_small_numbers(max_length_error) << std::endl;
    }

  // (2) The contact normals of both grains.
  const ContactParameters contact_parameters;
  const std::vector<bool> rigid = {false, false};
  // No prescribed velocities: rigid fields here are only flags.
  const std::vector<GrainInfo<dim>>       grains(rigid.size());
  const std::vector<GrainParameters<dim>> grain_parameters(rigid.size());
  const RigidGrainMotion<dim> rigid_motion(grains, grain_parameters, grid);
  const std::vector<bool>     keeps_shape(rigid.size(), false);
  GrainContact<dim>           contact(contact_parameters,
                            grid,
                            rigid_motion,
                            rigid,
                            keeps_shape,
                            grains,
                            grain_parameters);
  VectorType                  normals;
  contact.compute_normals(layout, mass_gradients, normals);

  double max_sum = 0., max_length_error = 0., min_nx_interior = 2.,
         min_nx_all       = 2.;
  unsigned int n_interior = 0;
  for (const unsigned int node : layout.contact_nodes())
    {
      AssertDimension(layout.node_slots_end(node) -
                        layout.node_slots_begin(node),
                      2);
      const unsigned int   s0  = layout.node_slots_begin(node);
      const unsigned int   a   = (layout.field(s0) == 0 ? s0 : s0 + 1);
      const unsigned int   b   = (a == s0 ? s0 + 1 : s0);
      const Tensor<1, dim> n_a = slot_vector(normals, a);
      const Tensor<1, dim> n_b = slot_vector(normals, b);
      max_sum                  = std::max(max_sum, (n_a + n_b).norm());
      max_length_error         = std::max(
        {max_length_error, std::abs(n_a.norm() - 1), std::abs(n_b.norm() - 1)});
      min_nx_all = std::min(min_nx_all, n_a[0]);
      if (is_interior(node))
        {
          min_nx_interior = std::min(min_nx_interior, n_a[0]);
          ++n_interior;
        }
    }
  deallog << "contact nodes: " << layout.contact_nodes().size() << " ("
          << n_interior << " interior)" << std::endl;
  deallog << "max |n_a + n_b| = " << filter_out_small_numbers(max_sum)
          << ", max ||n| - 1| = " << filter_out_small_numbers(max_length_error)
          << std::endl;
  deallog << "min n_a . e_x at interior contact nodes = " << min_nx_interior
          << std::endl;
  // Where the interface meets a face of the box, both grains also have a
  // free surface (the face), and g_a - g_b tilts towards the face normal
  // because the heavier grain 1 has more mass there: the normals stay
  // antiparallel unit vectors but are not e_x (a property of mass-gradient
  // normals, printed to document it).
  deallog << "min n_a . e_x at contact nodes on the box faces = " << min_nx_all
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
