// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/time_integration/implicit/elastic_preconditioner.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>

namespace grainmpm
{
  namespace
  {
    /**
     * The entries of particle @p p of @p cache whose slots are unknowns,
     * into @p entries.
     */
    template <int dim>
    void
    collect_unknown_entries(const TransferCache<dim>  &cache,
                            const std::vector<bool>   &unknown,
                            const std::size_t          p,
                            std::vector<unsigned int> &entries)
    {
      entries.clear();
      cache.for_each_entry(p, [&](const unsigned int e) {
        if (unknown[cache.slots[e]])
          entries.push_back(e);
      });
    }
  } // namespace



  template <int dim>
  void
  ElasticPreconditioner<dim>::setup(
    const GrainFieldLayout<dim>                       &layout,
    const std::vector<bool>                           &owned_unknown,
    const VectorType                                  &masses,
    const typename SlotProjection<dim>::LinearMap     &linear_projection,
    const TransferCache<dim>                          &cache,
    const std::vector<const ConstitutiveModel<dim> *> &models,
    const std::vector<double>                         &volumes,
    const MassMatrix<dim>                             &mass_matrix,
    const double                                       factor,
    const VectorType                                  &layout_vector,
    const bool                                         new_pattern)
  {
    const unsigned int n_owned = layout.n_slots();
    const unsigned int n_local = layout.n_local_slots();
    VectorType         probe;
    probe.reinit(layout_vector, true);

    // The unknowns among the owned and ghost slots: a probe of ones.
    std::vector<bool> unknown(n_local, false);
    probe = 0.;
    for (unsigned int s = 0; s < n_owned; ++s)
      if (owned_unknown[s])
        probe.local_element(s * dim) = 1.;
    probe.update_ghost_values();
    for (unsigned int s = 0; s < n_local; ++s)
      unknown[s] = probe.local_element(s * dim) != 0.;
    probe.zero_out_ghost_values();

    // The groups of the slots of a node are kept with the pattern.
    if (new_pattern)
      projection.reinit_groups(layout);
    projection.probe(layout, unknown, linear_projection, probe);

    // The lumped masses that divide the residual, of the owned and ghost
    // slots (Q needs both); for the rows that are not unknowns (rigid,
    // light slots: J = I) the mean of those, to keep A balanced.
    double sums[2] = {0., 0.};
    for (unsigned int s = 0; s < n_owned; ++s)
      if (unknown[s])
        {
          sums[0] += masses.local_element(s);
          sums[1] += 1.;
        }
    Utilities::MPI::sum(ArrayView<const double>(sums, 2),
                        layout.get_communicator(),
                        ArrayView<double>(sums, 2));
    const double mean = sums[1] > 0. ? sums[0] / sums[1] : 1.;
    VectorType   ghosted_masses(masses);
    ghosted_masses.update_ghost_values();
    std::vector<double> local_masses(n_local);
    for (unsigned int s = 0; s < n_local; ++s)
      local_masses[s] = unknown[s] ? ghosted_masses.local_element(s) : mean;

    initialize(cache,
               models,
               volumes,
               mass_matrix,
               local_masses,
               unknown,
               factor,
               layout_vector,
               new_pattern);
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::initialize(
    const TransferCache<dim>                          &cache,
    const std::vector<const ConstitutiveModel<dim> *> &models,
    const std::vector<double>                         &volumes,
    const MassMatrix<dim>                             &mass_matrix,
    const std::vector<double>                         &masses,
    const std::vector<bool>                           &unknown,
    const double                                       factor,
    const VectorType                                  &layout_vector,
    const bool                                         new_pattern)
  {
    const auto        &partitioner   = *layout_vector.get_partitioner();
    const unsigned int n_owned       = layout_vector.locally_owned_size();
    const unsigned int n_local       = n_owned + partitioner.n_ghost_indices();
    const unsigned int n_local_slots = n_local / dim;

    if (new_pattern || matrix.m() == 0)
      {
        // Once per step (the slots and points, not the contact status):
        // the raw matrix theta^2 dt^2 K + the consistent mass off the
        // diagonal, and the pattern of A.
        build_raw_pattern(cache, models, unknown, n_local_slots);
        assemble_raw_blocks(
          cache, models, volumes, mass_matrix, unknown, factor);
        build_pattern(unknown, n_owned / dim, n_local_slots);
        reinit_matrix(partitioner);
      }
    else
      matrix = 0.;
    values.assign(columns.size(), 0.);

    setup_q_blocks(masses, n_local_slots);
    assemble_mass_terms(mass_matrix, masses, unknown, n_owned / dim);
    assemble_stiffness_terms(unknown, n_local_slots);

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

    // The V-cycle also where the symmetric part is not positive definite.
    factorised =
      inverse == Inverse::cholesky && cholesky.factorize(matrix, new_pattern);
    if (!factorised)
      setup_multigrid(n_owned);
    weighted.reinit(layout_vector.get_partitioner());
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::build_raw_pattern(
    const TransferCache<dim>                          &cache,
    const std::vector<const ConstitutiveModel<dim> *> &models,
    const std::vector<bool>                           &unknown,
    const unsigned int                                 n_local_slots)
  {
    // The particles of each slot (grain by grain, a point couples the
    // nodes of 2 (linear) or 3 (GIMP) cells per axis), ...
    std::vector<unsigned int> entries;
    std::vector<unsigned int> slot_start(n_local_slots + 1, 0);
    for (std::size_t p = 0; p < models.size(); ++p)
      if (models[p] != nullptr)
        {
          collect_unknown_entries(cache, unknown, p, entries);
          for (const unsigned int e : entries)
            ++slot_start[cache.slots[e] + 1];
        }
    for (unsigned int s = 0; s < n_local_slots; ++s)
      slot_start[s + 1] += slot_start[s];
    std::vector<unsigned int> slot_particles(slot_start.back());
    {
      std::vector<unsigned int> fill(slot_start.begin(), slot_start.end() - 1);
      for (std::size_t p = 0; p < models.size(); ++p)
        if (models[p] != nullptr)
          {
            collect_unknown_entries(cache, unknown, p, entries);
            for (const unsigned int e : entries)
              slot_particles[fill[cache.slots[e]]++] = p;
          }
    }
    // ... and the slots that share a particle with each slot.
    std::vector<unsigned int> mark(n_local_slots,
                                   numbers::invalid_unsigned_int);
    raw_start.assign(n_local_slots + 1, 0);
    raw_columns.clear();
    for (unsigned int a = 0; a < n_local_slots; ++a)
      {
        const std::size_t first = raw_columns.size();
        for (unsigned int k = slot_start[a]; k < slot_start[a + 1]; ++k)
          {
            collect_unknown_entries(cache, unknown, slot_particles[k], entries);
            for (const unsigned int e : entries)
              if (mark[cache.slots[e]] != a)
                {
                  mark[cache.slots[e]] = a;
                  raw_columns.push_back(cache.slots[e]);
                }
          }
        std::sort(raw_columns.begin() + first, raw_columns.end());
        raw_start[a + 1] = raw_columns.size();
      }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::assemble_raw_blocks(
    const TransferCache<dim>                          &cache,
    const std::vector<const ConstitutiveModel<dim> *> &models,
    const std::vector<double>                         &volumes,
    const MassMatrix<dim>                             &mass_matrix,
    const std::vector<bool>                           &unknown,
    const double                                       factor)
  {
    raw_stiffness.assign(raw_columns.size(), Tensor<2, dim>());
    raw_mass.assign(raw_columns.size(), 0.);
    const bool   lumped   = mass_matrix.is_lumped();
    const double fraction = lumped ? 0. : mass_matrix.get_fraction();
    const std::vector<double> &shapes = mass_matrix.get_consistent_shapes();
    std::vector<unsigned int>  entries;
    for (std::size_t p = 0; p < models.size(); ++p)
      if (models[p] != nullptr)
        {
          collect_unknown_entries(cache, unknown, p, entries);
          const unsigned int n    = entries.size();
          const auto [lambda, mu] = models[p]->lame_parameters();
          const double scale      = factor * volumes[p];
          const double mass =
            lumped ? 0. : fraction * mass_matrix.get_particle_masses()[p];
          for (unsigned int a = 0; a < n; ++a)
            {
              const unsigned int    slot_a = cache.slots[entries[a]];
              const Tensor<1, dim> &ga     = cache.shape_gradients[entries[a]];
              const auto first = raw_columns.begin() + raw_start[slot_a];
              const auto last  = raw_columns.begin() + raw_start[slot_a + 1];
              for (unsigned int b = 0; b < n; ++b)
                {
                  const unsigned int slot_b = cache.slots[entries[b]];
                  const std::size_t  k =
                    std::lower_bound(first, last, slot_b) - raw_columns.begin();
                  const Tensor<1, dim> &gb  = cache.shape_gradients[entries[b]];
                  const double          dot = ga * gb;
                  Tensor<2, dim>       &block = raw_stiffness[k];
                  for (unsigned int i = 0; i < dim; ++i)
                    for (unsigned int j = 0; j < dim; ++j)
                      block[i][j] +=
                        scale * (lambda * ga[i] * gb[j] + mu * ga[j] * gb[i] +
                                 (i == j ? mu * dot : 0.));
                  // (The lumped mass has no consistent shapes.)
                  if (!lumped && a != b)
                    raw_mass[k] +=
                      mass * shapes[entries[a]] * shapes[entries[b]];
                }
            }
        }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::build_pattern(const std::vector<bool> &unknown,
                                            const unsigned int n_owned_slots,
                                            const unsigned int n_local_slots)
  {
    // P couples the slots of a node (SlotProjection::groups), so row r has
    // the columns of the raw rows of its node's slots, each widened to its
    // node's slots.
    const auto group = [&](const unsigned int slot) {
      return std::make_pair(projection.groups.begin() +
                              projection.group_start[slot],
                            projection.groups.begin() +
                              projection.group_start[slot + 1]);
    };
    std::vector<unsigned int> mark(n_local_slots,
                                   numbers::invalid_unsigned_int);
    std::vector<unsigned int> slot_columns_start(n_local_slots + 1, 0);
    std::vector<unsigned int> slot_columns;
    const auto                add_column = [&](const unsigned int row,
                                const unsigned int column) {
      if (unknown[column] && mark[column] != row)
        {
          mark[column] = row;
          slot_columns.push_back(column);
        }
    };
    for (unsigned int r = 0; r < n_local_slots; ++r)
      {
        const std::size_t first = slot_columns.size();
        if (!unknown[r])
          {
            if (r < n_owned_slots)
              slot_columns.push_back(r);
          }
        else
          {
            const auto [g_begin, g_end] = group(r);
            for (auto g = g_begin; g != g_end; ++g)
              {
                add_column(r, *g);
                for (unsigned int k = raw_start[*g]; k < raw_start[*g + 1]; ++k)
                  {
                    const auto [c_begin, c_end] = group(raw_columns[k]);
                    for (auto c = c_begin; c != c_end; ++c)
                      add_column(r, *c);
                  }
              }
          }
        std::sort(slot_columns.begin() + first, slot_columns.end());
        slot_columns_start[r + 1] = slot_columns.size();
      }
    row_start.assign(n_local_slots * dim + 1, 0);
    columns.clear();
    for (unsigned int s = 0; s < n_local_slots; ++s)
      for (unsigned int i = 0; i < dim; ++i)
        {
          for (unsigned int k = slot_columns_start[s];
               k < slot_columns_start[s + 1];
               ++k)
            for (unsigned int j = 0; j < dim; ++j)
              columns.push_back(slot_columns[k] * dim + j);
          row_start[s * dim + i + 1] = columns.size();
        }
    // Where each raw block lands without projection: its offset in the
    // row of its slot.
    raw_offsets.resize(raw_columns.size());
    for (unsigned int a = 0; a < n_local_slots; ++a)
      for (unsigned int k = raw_start[a]; k < raw_start[a + 1]; ++k)
        raw_offsets[k] =
          dim *
          (std::lower_bound(slot_columns.begin() + slot_columns_start[a],
                            slot_columns.begin() + slot_columns_start[a + 1],
                            raw_columns[k]) -
           (slot_columns.begin() + slot_columns_start[a]));
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::reinit_matrix(
    const Utilities::MPI::Partitioner &partitioner)
  {
    global_columns.resize(columns.size());
    for (unsigned int j = 0; j < columns.size(); ++j)
      global_columns[j] = partitioner.local_to_global(columns[j]);

    const IndexSet &owned    = partitioner.locally_owned_range();
    IndexSet        writable = owned;
    writable.add_indices(partitioner.ghost_indices());
    TrilinosWrappers::SparsityPattern sparsity(
      owned, owned, writable, partitioner.get_mpi_communicator());
    const unsigned int n_local = row_start.size() - 1;
    for (unsigned int k = 0; k < n_local; ++k)
      if (row_start[k + 1] > row_start[k])
        sparsity.add_entries(partitioner.local_to_global(k),
                             global_columns.begin() + row_start[k],
                             global_columns.begin() + row_start[k + 1]);
    sparsity.compress();
    matrix.reinit(sparsity);
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::add_block(const unsigned int    row,
                                        const unsigned int    column,
                                        const Tensor<2, dim> &block)
  {
    // A[row slot][column slot] += block, in the local CSR (the dim
    // unknowns of a slot are consecutive columns).
    for (unsigned int i = 0; i < dim; ++i)
      {
        const auto    first = columns.begin() + row_start[row * dim + i];
        const auto    last  = columns.begin() + row_start[row * dim + i + 1];
        double *const entry =
          values.data() +
          (std::lower_bound(first, last, column * dim) - columns.begin());
        for (unsigned int k = 0; k < dim; ++k)
          entry[k] += block[i][k];
      }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::setup_q_blocks(const std::vector<double> &masses,
                                             const unsigned int n_local_slots)
  {
    // The columns of Q = M_L P M_L^-1: the rows r with Q_ra != 0 for each
    // slot a, and Q_ra = m_r P_ra / m_a.
    q_start.assign(n_local_slots + 1, 0);
    for (unsigned int r = 0; r < n_local_slots; ++r)
      for (unsigned int k = projection.start[r]; k < projection.start[r + 1];
           ++k)
        ++q_start[projection.partners[k] + 1];
    for (unsigned int a = 0; a < n_local_slots; ++a)
      q_start[a + 1] += q_start[a];
    q_rows.resize(q_start.back());
    q_blocks.resize(q_start.back());
    std::vector<unsigned int> fill(q_start.begin(), q_start.end() - 1);
    for (unsigned int r = 0; r < n_local_slots; ++r)
      for (unsigned int k = projection.start[r]; k < projection.start[r + 1];
           ++k)
        {
          const unsigned int a = projection.partners[k];
          q_rows[fill[a]]      = r;
          q_blocks[fill[a]++]  = (masses[r] / masses[a]) * projection.blocks[k];
        }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::assemble_mass_terms(
    const MassMatrix<dim>     &mass_matrix,
    const std::vector<double> &masses,
    const std::vector<bool>   &unknown,
    const unsigned int         n_owned_slots)
  {
    // Slots that P leaves alone and that no other slot's row refers to:
    // their raw blocks go in unchanged (assemble_stiffness_terms()).
    const Tensor<2, dim> identity      = unit_symmetric_tensor<dim>();
    const unsigned int   n_local_slots = q_start.size() - 1;
    plain.assign(n_local_slots, false);
    for (unsigned int s = 0; s < n_local_slots; ++s)
      plain[s] = unknown[s] &&
                 projection.start[s + 1] == projection.start[s] + 1 &&
                 projection.partners[projection.start[s]] == s &&
                 projection.blocks[projection.start[s]] == identity &&
                 q_start[s + 1] == q_start[s] + 1;

    // M_L (I - P) and Q D, D the diagonal of M, on the owned slots;
    // m_s delta for the slots that are not unknowns (J = I).
    const bool lumped = mass_matrix.is_lumped();
    dof_weights.resize(n_owned_slots * dim);
    for (unsigned int s = 0; s < n_owned_slots; ++s)
      {
        const double m = masses[s];
        for (unsigned int i = 0; i < dim; ++i)
          dof_weights[s * dim + i] = m;
        add_block(s, s, m * identity);
        if (!unknown[s])
          continue;
        for (unsigned int k = projection.start[s]; k < projection.start[s + 1];
             ++k)
          add_block(s, projection.partners[k], -m * projection.blocks[k]);
        const double D =
          lumped ? m : mass_matrix.get_diagonal().local_element(s * dim);
        for (unsigned int k = q_start[s]; k < q_start[s + 1]; ++k)
          add_block(q_rows[k], s, D * q_blocks[k]);
      }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::assemble_stiffness_terms(
    const std::vector<bool> &unknown,
    const unsigned int       n_local_slots)
  {
    // Q (theta^2 dt^2 K) P + Q M_C, M_C the consistent mass off the
    // diagonal.
    for (unsigned int a = 0; a < n_local_slots; ++a)
      for (unsigned int k = raw_start[a]; k < raw_start[a + 1]; ++k)
        {
          const unsigned int b = raw_columns[k];
          if (plain[a] && plain[b])
            {
              Tensor<2, dim> block = raw_stiffness[k];
              for (unsigned int i = 0; i < dim; ++i)
                block[i][i] += raw_mass[k];
              for (unsigned int i = 0; i < dim; ++i)
                {
                  double *const entry =
                    values.data() + row_start[a * dim + i] + raw_offsets[k];
                  for (unsigned int j = 0; j < dim; ++j)
                    entry[j] += block[i][j];
                }
              continue;
            }
          for (unsigned int q = q_start[a]; q < q_start[a + 1]; ++q)
            {
              const unsigned int row = q_rows[q];
              if (!unknown[row])
                continue;
              if (raw_mass[k] != 0.)
                add_block(row, b, raw_mass[k] * q_blocks[q]);
              const Tensor<2, dim> left = q_blocks[q] * raw_stiffness[k];
              for (unsigned int j = projection.start[b];
                   j < projection.start[b + 1];
                   ++j)
                add_block(row,
                          projection.partners[j],
                          left * projection.blocks[j]);
            }
        }
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::setup_multigrid(const unsigned int n_owned)
  {
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
  }



  template <int dim>
  void
  ElasticPreconditioner<dim>::vmult(VectorType       &dst,
                                    const VectorType &src) const
  {
    const unsigned int n = dof_weights.size();
    for (unsigned int k = 0; k < n; ++k)
      weighted.local_element(k) = dof_weights[k] * src.local_element(k);
    if (factorised)
      cholesky.solve(dst.begin(), weighted.begin());
    else
      amg.vmult(dst, weighted);
  }



  template class ElasticPreconditioner<2>;
  template class ElasticPreconditioner<3>;
} // namespace grainmpm
