// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// GrainContact::apply_contact and apply_walls on a grid: two half-space
// grains driven into each other. At every contact node the momentum is
// conserved and no field approaches any more; slots at other nodes are not
// touched; node_in_contact marks exactly the corrected nodes. apply_walls
// stops every motion into a wall (no slip: zero velocity) and leaves the
// open face and the interior alone. Both without the gap check (it needs
// the slot volumes, which the grains here do not have): every approach at
// a contact node is removed.

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

  BackgroundGridParameters<dim> parameters;
  parameters.n_cells                  = std::vector<unsigned int>(dim, 4);
  parameters.boundary_conditions_text = "x-: no slip, x+: open, y-: free slip, "
                                        "y+: friction 0.5";
  parameters.check();
  BackgroundGrid<dim> grid(parameters, MPI_COMM_WORLD);

  // Grain 0 (mass 1 per point) in x < 0.375 moving with (1, 0.3, 0.1),
  // grain 1 (mass 3) in x > 0.375 moving with (-0.5, 0, 0).
  Particles::ParticleHandler<dim> particle_handler(grid.get_triangulation(),
                                                   grid.get_mapping(),
                                                   Layout::n_properties);
  Tensor<1, dim>                  velocity_0, velocity_1;
  velocity_0[0] = 1.;
  velocity_0[1] = 0.3;
  if (dim == 3)
    velocity_0[dim - 1] = 0.1;
  velocity_1[0] = -0.5;
  insert_half_space_grains(
    grid, particle_handler, 0.375, velocity_0, velocity_1);

  TransferCache<dim> cache;
  cache.reinit(grid, particle_handler, {0, 1});
  GrainFieldLayout<dim> layout;
  layout.reinit(cache, grid);

  // P2G of mass, momentum and mass gradient.
  VectorType masses, velocities, mass_gradients;
  layout.reinit_vector(masses, 1);
  layout.reinit_vector(velocities, dim);
  layout.reinit_vector(mass_gradients, dim);
  {
    unsigned int p = 0;
    for_each_particle(grid,
                      particle_handler,
                      [&](const auto &, const auto &particle) {
                        const auto   properties = particle->get_properties();
                        const double m          = properties[Layout::mass];
                        const auto   v = Layout::get_velocity(properties);
                        for (unsigned int k = cache.first_entry[p];
                             k < cache.first_entry[p + 1];
                             ++k)
                          {
                            const unsigned int s = cache.slots[k];
                            masses.local_element(s) +=
                              m * cache.shape_values[k];
                            for (unsigned int d = 0; d < dim; ++d)
                              {
                                velocities.local_element(s * dim + d) +=
                                  m * cache.shape_values[k] * v[d];
                                mass_gradients.local_element(s * dim + d) +=
                                  m * cache.shape_gradients[k][d];
                              }
                          }
                        ++p;
                      });
  }
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    for (unsigned int d = 0; d < dim; ++d)
      velocities.local_element(s * dim + d) /= masses.local_element(s);

  auto get = [&](const VectorType &vector, const unsigned int s) {
    Tensor<1, dim> value;
    for (unsigned int d = 0; d < dim; ++d)
      value[d] = vector.local_element(s * dim + d);
    return value;
  };

  const std::vector<bool> rigid = {false, false};

  // No prescribed velocities: rigid fields here are only flags.

  const std::vector<GrainInfo<dim>>       grains(rigid.size());
  const std::vector<GrainParameters<dim>> grain_parameters(rigid.size());
  const RigidGrainMotion<dim> rigid_motion(grains, grain_parameters, grid);
  const std::vector<bool>     keeps_shape(rigid.size(), false);
  for (const auto model :
       {ContactModel::frictionless, ContactModel::coulomb_friction})
    {
      ContactParameters contact_parameters;
      contact_parameters.model                = model;
      contact_parameters.friction_coefficient = 0.2;
      contact_parameters.gap_check            = false;
      deallog << (model == ContactModel::frictionless ? "frictionless" :
                                                        "Coulomb friction")
              << std::endl;
      GrainContact<dim> contact(contact_parameters,
                                grid,
                                rigid_motion,
                                rigid,
                                keeps_shape,
                                grains,
                                grain_parameters);
      VectorType        normals;
      contact.compute_normals(layout, mass_gradients, normals);

      VectorType                 corrected = velocities;
      std::vector<unsigned char> node_in_contact(grid.n_nodes(), 0);
      const unsigned int         n_corrected = contact.apply_contact(
        layout, masses, normals, corrected, &node_in_contact);

      double       max_momentum_error = 0., max_approach = 0.;
      unsigned int n_flagged = 0, n_other_changed = 0;
      for (unsigned int node = 0; node < grid.n_nodes(); ++node)
        {
          const unsigned int begin = layout.node_slots_begin(node);
          const unsigned int end   = layout.node_slots_end(node);
          n_flagged += node_in_contact[node];
          if (end - begin < 2)
            {
              for (unsigned int s = begin; s < end; ++s)
                if (get(corrected, s) != get(velocities, s))
                  ++n_other_changed;
              continue;
            }
          Tensor<1, dim> before, after;
          double         mass = 0., scale = 0.;
          for (unsigned int s = begin; s < end; ++s)
            {
              const double m = masses.local_element(s);
              before += m * get(velocities, s);
              after += m * get(corrected, s);
              mass += m;
              scale += m * get(velocities, s).norm();
            }
          max_momentum_error =
            std::max(max_momentum_error, (after - before).norm() / scale);
          for (unsigned int s = begin; s < end; ++s)
            max_approach = std::max(max_approach,
                                    (get(corrected, s) - before / mass) *
                                      get(normals, s) * mass / scale);
        }
      deallog << "contact nodes: " << layout.contact_nodes().size()
              << ", corrected: " << n_corrected << ", flagged: " << n_flagged
              << std::endl;
      deallog << "max |momentum change| / scale at a node = "
              << filter_out_small_numbers(max_momentum_error)
              << ", max (v_g - v_cm) . n_g after / scale = "
              << filter_out_small_numbers(max_approach)
              << ", slots changed at single-field nodes: " << n_other_changed
              << std::endl;
    }

  // Walls.
  ContactParameters contact_parameters;
  contact_parameters.gap_check = false;
  GrainContact<dim> contact(contact_parameters,
                            grid,
                            rigid_motion,
                            rigid,
                            keeps_shape,
                            grains,
                            grain_parameters);
  VectorType        walled = velocities;
  contact.apply_walls(layout, walled);
  unsigned int n_into_wall = 0, n_no_slip_moving = 0, n_changed_elsewhere = 0,
               n_boundary_slots = 0, n_into_wall_before = 0;
  for (unsigned int node = 0; node < grid.n_nodes(); ++node)
    for (unsigned int s = layout.node_slots_begin(node);
         s < layout.node_slots_end(node);
         ++s)
      {
        const unsigned int faces = grid.node_faces(node);
        const auto         v     = get(walled, s);
        bool               wall  = false;
        for (unsigned int face = 0; face < 2 * dim; ++face)
          if ((faces & (1U << face)) &&
              grid.boundary_condition(face).type != BoundaryType::open)
            {
              wall                 = true;
              const double outward = (face % 2 == 0 ? -1. : 1.);
              if (outward * v[face / 2] > 1e-14)
                ++n_into_wall;
              if (outward * get(velocities, s)[face / 2] > 1e-14)
                ++n_into_wall_before;
              if (grid.boundary_condition(face).type == BoundaryType::no_slip &&
                  v.norm() != 0.)
                ++n_no_slip_moving;
            }
        if (wall)
          ++n_boundary_slots;
        else if (v != get(velocities, s))
          ++n_changed_elsewhere;
      }
  deallog << "walls: slots at wall nodes: " << n_boundary_slots
          << ", moving into a wall before: " << n_into_wall_before
          << ", after: " << n_into_wall
          << ", moving at a no-slip wall: " << n_no_slip_moving
          << ", changed away from walls: " << n_changed_elsewhere << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
