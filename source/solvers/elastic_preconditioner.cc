// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/solvers/elastic_preconditioner.h>

#include <deal.II/base/index_set.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>

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
    const VectorType                                  &layout_vector,
    const bool                                         new_pattern)
  {
    using size_type                 = types::global_dof_index;
    const auto        &partitioner  = *layout_vector.get_partitioner();
    const MPI_Comm     communicator = partitioner.get_mpi_communicator();
    const unsigned int n_owned      = layout_vector.locally_owned_size();
    const unsigned int n_local      = n_owned + partitioner.n_ghost_indices();

    // The local unknowns (slot * dim + d, owned and ghost) of the entries
    // of particle p whose slot is an unknown.
    std::vector<unsigned int> dofs;
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
          dofs.push_back(slot * dim + d);
      });
    };

    // The pattern, in local numbers (CSR over the owned and ghost rows),
    // and the Trilinos matrix with it: a point couples the nodes of 2
    // (linear) or 3 (GIMP) cells per axis. It depends on the slots and the
    // points only, not on the contact status, and is kept between calls
    // without @p new_pattern.
    if (new_pattern || matrix.m() == 0)
      {
        // Slot by slot (the dim unknowns of a slot share their columns),
        // then expanded to the unknowns.
        const unsigned int                     n_local_slots = n_local / dim;
        std::vector<std::vector<unsigned int>> slot_columns(n_local_slots);
        for (unsigned int s = 0; s < n_owned / dim; ++s)
          slot_columns[s].push_back(s);
        std::vector<unsigned int> slots;
        for (std::size_t p = 0; p < models.size(); ++p)
          if (models[p] != nullptr)
            {
              collect(p);
              slots.clear();
              for (unsigned int a = 0; a < entries.size(); ++a)
                slots.push_back(dofs[a * dim] / dim);
              for (const unsigned int slot : slots)
                slot_columns[slot].insert(slot_columns[slot].end(),
                                          slots.begin(),
                                          slots.end());
            }
        row_start.assign(n_local + 1, 0);
        columns.clear();
        for (unsigned int s = 0; s < n_local_slots; ++s)
          {
            std::vector<unsigned int> &list = slot_columns[s];
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
            for (unsigned int i = 0; i < dim; ++i)
              {
                for (const unsigned int column : list)
                  for (unsigned int k = 0; k < dim; ++k)
                    columns.push_back(column * dim + k);
                row_start[s * dim + i + 1] = columns.size();
              }
          }
        global_columns.resize(columns.size());
        for (unsigned int j = 0; j < columns.size(); ++j)
          global_columns[j] = partitioner.local_to_global(columns[j]);

        const IndexSet &owned    = partitioner.locally_owned_range();
        IndexSet        writable = owned;
        writable.add_indices(partitioner.ghost_indices());
        TrilinosWrappers::SparsityPattern sparsity(owned,
                                                   owned,
                                                   writable,
                                                   communicator);
        for (unsigned int k = 0; k < n_local; ++k)
          if (row_start[k + 1] > row_start[k])
            sparsity.add_entries(partitioner.local_to_global(k),
                                 global_columns.begin() + row_start[k],
                                 global_columns.begin() + row_start[k + 1]);
        sparsity.compress();
        matrix.reinit(sparsity);
      }
    else
      matrix = 0.;
    values.assign(columns.size(), 0.);
    // A[row][column] += value, in the local CSR.
    const auto add = [&](const unsigned int row,
                         const unsigned int column,
                         const double       value) {
      const auto first = columns.begin() + row_start[row];
      const auto last  = columns.begin() + row_start[row + 1];
      values[std::lower_bound(first, last, column) - columns.begin()] += value;
    };

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
        for (unsigned int i = 0; i < dim; ++i)
          {
            dof_weights[s * dim + i] = m;
            for (unsigned int k = 0; k < dim; ++k)
              add(s * dim + i, s * dim + k, block[i][k]);
          }
      }

    // From the points: theta^2 dt^2 P_a K_ab P_b, and the consistent mass
    // alpha m_p S_a S_b P_a off the diagonal, with
    // K_(a i)(b k) = V (lambda G_a,i G_b,k + mu G_a,k G_b,i
    //                   + mu delta_ik G_a . G_b).
    const std::vector<double> &shapes = mass_matrix.get_consistent_shapes();
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
                  // The dim unknowns of a slot are consecutive columns.
                  for (unsigned int i = 0; i < dim; ++i)
                    {
                      const unsigned int row = dofs[a * dim + i];
                      const auto    first    = columns.begin() + row_start[row];
                      const auto    last = columns.begin() + row_start[row + 1];
                      double *const entry =
                        values.data() +
                        (std::lower_bound(first, last, dofs[b * dim]) -
                         columns.begin());
                      for (unsigned int k = 0; k < dim; ++k)
                        entry[k] += projected[i][k];
                    }
                }
            }
        }

    // Into the Trilinos matrix row by row; ghost rows go to their owners.
    for (unsigned int k = 0; k < n_local; ++k)
      if (row_start[k + 1] > row_start[k])
        matrix.add(partitioner.local_to_global(k),
                   row_start[k + 1] - row_start[k],
                   global_columns.data() + row_start[k],
                   values.data() + row_start[k],
                   false,
                   false);
    matrix.compress(VectorOperation::add);

    // Smoothed aggregation for a vector problem: one near-null-space mode
    // per displacement component. (PreconditionAMG::reinit(), which keeps
    // the aggregates of the last setup, gave 73 instead of 19 GMRES
    // iterations per Newton step on a packing after status changes.)
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    data.constant_modes.assign(dim, std::vector<bool>(n_owned, false));
    for (unsigned int k = 0; k < n_owned; ++k)
      data.constant_modes[k % dim][k] = true;
    // A small coarsest level: with deal.II's default of 2000 unknowns its
    // direct solve (KLU) took 45 % of the time of the 3D sphere test run
    // (tests/runs/sphere_rebound_3d_implicit with AMG; 500: half the time).
    Teuchos::ParameterList              parameters;
    std::unique_ptr<Epetra_MultiVector> modes;
    data.set_parameters(parameters, modes, matrix.trilinos_matrix());
    parameters.set("coarse: max size", 500);
    amg.initialize(matrix, parameters);
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
