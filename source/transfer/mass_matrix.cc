// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/mass_matrix.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <algorithm>

namespace grainmpm
{
  template <int dim>
  void
  MassMatrix<dim>::reinit(
    const Transfer<dim>                   &transfer,
    const Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                      &lumped_masses,
    const double                           fraction)
  {
    Assert(fraction >= 0. && fraction <= 1.,
           ExcMessage("The consistent mass fraction lies in [0, 1]."));
    using Layout        = MaterialPointLayout<dim>;
    this->transfer      = &transfer;
    this->lumped_masses = &lumped_masses;
    this->fraction      = fraction;

    const std::vector<GrainInfo<dim>> &grains = transfer.get_grains();
    const std::size_t n_particles = transfer.get_cache().n_particles();
    particle_masses.resize(is_lumped() ? 0 : n_particles);
    double largest_mass = 0.;
    transfer.for_each_particle(
      particle_handler, [&](const std::size_t p, const auto &particle) {
        const auto   properties = particle->get_properties();
        const double mass       = properties[Layout::mass];
        largest_mass            = std::max(largest_mass, mass);
        if (!is_lumped())
          particle_masses[p] =
            grains[Layout::get_grain(properties)].rigid ? 0. : mass;
      });
    light_threshold =
      1e-6 * Utilities::MPI::max(largest_mass,
                                 transfer.get_layout().get_communicator());
    if (is_lumped())
      return;

    // Lumped rows: rigid and light slots, owned and ghost.
    const GrainFieldLayout<dim> &layout         = transfer.get_layout();
    const std::vector<bool>     &field_is_rigid = transfer.get_field_is_rigid();
    const unsigned int           n_local =
      layout.n_slots() + lumped_masses.get_partitioner()->n_ghost_indices();
    slot_rigid.resize(layout.n_slots());
    slot_lumped.resize(n_local);
    lumped_masses.update_ghost_values();
    for (unsigned int s = 0; s < n_local; ++s)
      {
        const bool rigid = field_is_rigid[layout.field(s)];
        if (s < layout.n_slots())
          slot_rigid[s] = rigid;
        slot_lumped[s] = rigid || lumped_masses.begin()[s] <= light_threshold;
      }
    lumped_masses.zero_out_ghost_values();

    // The weights of the consistent part per entry (zero at lumped slots)
    // and the weight of the lumped slots per particle; the diagonal
    // (1 - alpha) m_i + alpha sum_p m_p S_ip (S_ip + that weight), m_i for
    // lumped rows.
    const TransferCache<dim> &cache = transfer.get_cache();
    consistent_shapes.resize(cache.n_entries());
    lumped_weights.assign(particle_masses.size(), 0.);
    layout.reinit_vector(diagonal, dim);
    double *const values = diagonal.begin();
    for (std::size_t p = 0; p < particle_masses.size(); ++p)
      {
        cache.for_each_entry(p, [&](const unsigned int e) {
          const bool lumped    = slot_lumped[cache.slots[e]];
          consistent_shapes[e] = lumped ? 0. : cache.shape_values[e];
          if (lumped)
            lumped_weights[p] += cache.shape_values[e];
        });
        cache.for_each_entry(p, [&](const unsigned int e) {
          const double shape = cache.shape_values[e];
          for (unsigned int d = 0; d < dim; ++d)
            values[cache.slots[e] * dim + d] +=
              particle_masses[p] * shape * (shape + lumped_weights[p]);
        });
      }
    diagonal.compress(VectorOperation::add);
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      for (unsigned int d = 0; d < dim; ++d)
        {
          double &entry = diagonal.local_element(s * dim + d);
          entry         = slot_lumped[s] ?
                            lumped_masses.local_element(s) :
                            (1. - fraction) * lumped_masses.local_element(s) +
                      fraction * entry;
        }
  }



  template <int dim>
  void
  MassMatrix<dim>::add_consistent(const VectorType &src, VectorType &dst) const
  {
    const TransferCache<dim> &cache  = transfer->get_cache();
    const double *const       values = src.begin();
    double *const             output = dst.begin();
    // Per particle: the interpolation over its slots with a consistent
    // row (weights consistent_shapes, zero at lumped slots), and the weight
    // of its lumped slots, which acts on the diagonal. What this adds to
    // lumped rows is replaced by vmult().
    const double *const       shapes  = cache.shape_values.data();
    const double *const       weights = consistent_shapes.data();
    const unsigned int *const slots   = cache.slots.data();
    for (std::size_t p = 0; p < particle_masses.size(); ++p)
      {
        const double mass = particle_masses[p];
        if (mass == 0.)
          continue;
        double interpolated[dim] = {};
        cache.for_each_entry(p, [&](const unsigned int e) {
          for (unsigned int d = 0; d < dim; ++d)
            interpolated[d] += weights[e] * values[slots[e] * dim + d];
        });
        const double lumped_weight = lumped_weights[p];
        cache.for_each_entry(p, [&](const unsigned int e) {
          const double weight = mass * shapes[e];
          for (unsigned int d = 0; d < dim; ++d)
            output[slots[e] * dim + d] +=
              weight *
              (interpolated[d] + lumped_weight * values[slots[e] * dim + d]);
        });
      }
  }



  template <int dim>
  void
  MassMatrix<dim>::vmult(VectorType &dst, const VectorType &src) const
  {
    Assert(transfer != nullptr, ExcMessage("reinit() first."));
    const unsigned int n_slots = transfer->get_layout().n_slots();
    if (is_lumped())
      {
        for (unsigned int s = 0; s < n_slots; ++s)
          for (unsigned int d = 0; d < dim; ++d)
            dst.local_element(s * dim + d) =
              lumped_masses->local_element(s) * src.local_element(s * dim + d);
        return;
      }

    const bool had_ghosts = src.has_ghost_elements();
    if (!had_ghosts)
      src.update_ghost_values();
    dst = 0.;
    add_consistent(src, dst);
    dst.compress(VectorOperation::add);
    if (!had_ghosts)
      src.zero_out_ghost_values();
    for (unsigned int s = 0; s < n_slots; ++s)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const unsigned int k = s * dim + d;
          const double       lumped =
            lumped_masses->local_element(s) * src.local_element(k);
          dst.local_element(k) =
            slot_lumped[s] ?
              lumped :
              (1. - fraction) * lumped + fraction * dst.local_element(k);
        }
  }



  template <int dim>
  unsigned int
  MassMatrix<dim>::solve(const VectorType &momenta,
                         VectorType       &velocities) const
  {
    transfer->velocities_from_momenta(*lumped_masses, momenta, velocities);
    if (is_lumped())
      return 0;

    struct Jacobi
    {
      const VectorType &diagonal;

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        for (unsigned int k = 0; k < src.locally_owned_size(); ++k)
          dst.local_element(k) =
            src.local_element(k) / diagonal.local_element(k);
      }
    };
    SolverControl        control(1000, 1e-12 * momenta.l2_norm(), false, false);
    SolverCG<VectorType> cg(control);
    cg.solve(*this, velocities, momenta, Jacobi{diagonal});
    return control.last_step();
  }



  template <int dim>
  double
  MassMatrix<dim>::local_kinetic_energy(const VectorType &velocities) const
  {
    const GrainFieldLayout<dim> &layout     = transfer->get_layout();
    const std::vector<bool> &field_is_rigid = transfer->get_field_is_rigid();
    double                   energy         = 0.;
    if (is_lumped())
      {
        for (unsigned int s = 0; s < layout.n_slots(); ++s)
          if (!field_is_rigid[layout.field(s)])
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double v = velocities.local_element(s * dim + d);
                energy += 0.5 * lumped_masses->local_element(s) * v * v;
              }
        return energy;
      }
    VectorType product;
    product.reinit(velocities, true);
    vmult(product, velocities);
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      if (!slot_rigid[s])
        for (unsigned int d = 0; d < dim; ++d)
          energy += 0.5 * velocities.local_element(s * dim + d) *
                    product.local_element(s * dim + d);
    return energy;
  }



  template class MassMatrix<2>;
  template class MassMatrix<3>;
} // namespace grainmpm
