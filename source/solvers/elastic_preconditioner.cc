// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/solvers/elastic_preconditioner.h>

#include <deal.II/base/index_set.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

namespace grainmpm
{
  template <int dim>
  void
  ElasticPreconditioner<dim>::initialize(
    const TransferCache<dim>                          &cache,
    const std::vector<const ConstitutiveModel<dim> *> &models,
    const std::vector<double>                         &volumes,
    const MassMatrix<dim>                             &mass_matrix,
    const std::vector<double>                         &lumped_masses,
    const std::vector<bool>                           &unknown,
    const std::vector<Tensor<2, dim>>                 &projections,
    const double                                       factor,
    const VectorType                                  &layout_vector)
  {
    using size_type                 = types::global_dof_index;
    const auto        &partitioner  = *layout_vector.get_partitioner();
    const MPI_Comm     communicator = partitioner.get_mpi_communicator();
    const unsigned int n_owned      = layout_vector.locally_owned_size();
    const IndexSet    &owned        = partitioner.locally_owned_range();
    IndexSet           writable     = owned;
    writable.add_indices(partitioner.ghost_indices());

    std::vector<size_type>    dofs;
    std::vector<unsigned int> entries;
    const auto                collect = [&](const std::size_t p) {
      dofs.clear();
      entries.clear();
      cache.for_each_entry(p, [&](const unsigned int e) {
        const unsigned int slot = cache.slots[e];
        if (!unknown[slot])
          return;
        entries.push_back(e);
        for (unsigned int d = 0; d < dim; ++d)
          dofs.push_back(partitioner.local_to_global(slot * dim + d));
      });
    };

    // A point couples the nodes of 2 (linear) or 3 (GIMP) cells per axis.
    constexpr unsigned int            n_neighbours = (dim == 2 ? 25 : 125);
    TrilinosWrappers::SparsityPattern sparsity(
      owned, owned, writable, communicator, n_neighbours * dim);
    // The diagonal blocks of the owned slots.
    for (unsigned int k = 0; k < n_owned; ++k)
      {
        const size_type row = partitioner.local_to_global(k);
        for (unsigned int d = 0; d < dim; ++d)
          sparsity.add(row, row - k % dim + d);
      }
    for (std::size_t p = 0; p < models.size(); ++p)
      if (models[p] != nullptr)
        {
          collect(p);
          for (const size_type row : dofs)
            sparsity.add_entries(row, dofs.begin(), dofs.end());
        }
    sparsity.compress();
    matrix.reinit(sparsity);

    // The slot diagonal blocks D_s P_s + m_s (I - P_s), D_s the diagonal
    // of M; m_s delta for the slots that are not unknowns (J = I).
    const bool         lumped   = mass_matrix.is_lumped();
    const double       fraction = mass_matrix.get_fraction();
    const unsigned int n_slots  = n_owned / dim;
    dof_weights.resize(n_owned);
    for (unsigned int s = 0; s < n_slots; ++s)
      {
        const double m = lumped_masses[s];
        const double D =
          lumped ? m : mass_matrix.get_diagonal().local_element(s * dim);
        const Tensor<2, dim> P =
          unknown[s] ? projections[s] : unit_symmetric_tensor<dim>();
        const Tensor<2, dim> block =
          unknown[s] ?
            Tensor<2, dim>(D * P + m * (unit_symmetric_tensor<dim>() - P)) :
            Tensor<2, dim>(m * unit_symmetric_tensor<dim>());
        const size_type first = partitioner.local_to_global(s * dim);
        for (unsigned int i = 0; i < dim; ++i)
          {
            dof_weights[s * dim + i] = m;
            for (unsigned int k = 0; k < dim; ++k)
              matrix.add(first + i, first + k, block[i][k]);
          }
      }

    // From the points: theta^2 dt^2 P_a K_ab P_b, and the consistent mass
    // alpha m_p S_a S_b P_a off the diagonal, with
    // K_(a i)(b k) = V (lambda G_a,i G_b,k + mu G_a,k G_b,i
    //                   + mu delta_ik G_a . G_b).
    const std::vector<double> &shapes = mass_matrix.get_consistent_shapes();
    FullMatrix<double>         local;
    for (std::size_t p = 0; p < models.size(); ++p)
      if (models[p] != nullptr)
        {
          collect(p);
          const unsigned int n = entries.size();
          if (n == 0)
            continue;
          const auto [lambda, mu] = models[p]->lame_parameters();
          const double scale      = factor * volumes[p];
          const double mass =
            lumped ? 0. : fraction * mass_matrix.get_particle_masses()[p];
          local.reinit(n * dim, n * dim);
          for (unsigned int a = 0; a < n; ++a)
            {
              const Tensor<1, dim> &ga = cache.shape_gradients[entries[a]];
              const Tensor<2, dim> &pa = projections[cache.slots[entries[a]]];
              for (unsigned int b = 0; b < n; ++b)
                {
                  const Tensor<1, dim> &gb = cache.shape_gradients[entries[b]];
                  const Tensor<2, dim> &pb =
                    projections[cache.slots[entries[b]]];
                  Tensor<2, dim> block;
                  const double   dot = ga * gb;
                  for (unsigned int i = 0; i < dim; ++i)
                    for (unsigned int k = 0; k < dim; ++k)
                      block[i][k] =
                        scale * (lambda * ga[i] * gb[k] + mu * ga[k] * gb[i] +
                                 (i == k ? mu * dot : 0.));
                  Tensor<2, dim> projected = pa * block * pb;
                  if (a != b && mass != 0.)
                    projected +=
                      (mass * shapes[entries[a]] * shapes[entries[b]]) * pa;
                  for (unsigned int i = 0; i < dim; ++i)
                    for (unsigned int k = 0; k < dim; ++k)
                      local(a * dim + i, b * dim + k) = projected[i][k];
                }
            }
          matrix.add(dofs, local);
        }
    matrix.compress(VectorOperation::add);

    // Smoothed aggregation for a vector problem: one near-null-space mode
    // per displacement component.
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    data.constant_modes.assign(dim, std::vector<bool>(n_owned, false));
    for (unsigned int k = 0; k < n_owned; ++k)
      data.constant_modes[k % dim][k] = true;
    amg.initialize(matrix, data);
    weighted.reinit(layout_vector.get_partitioner());
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::vmult(VectorType       &dst,
                                    const VectorType &src) const
  {
    const unsigned int n = dof_weights.size();
    for (unsigned int k = 0; k < n; ++k)
      weighted.local_element(k) = dof_weights[k] * src.local_element(k);
    amg.vmult(dst, weighted);
  }



  template class ElasticPreconditioner<2>;
  template class ElasticPreconditioner<3>;
} // namespace grainmpm
