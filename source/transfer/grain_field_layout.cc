// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/transfer/grain_field_layout.h>

namespace grainmpm
{
  namespace
  {
    // Fields a node can hold. A node touches 2^dim cells; with a few grains
    // per cell 4 * 2^dim is far above what packings produce.
    template <int dim>
    constexpr unsigned int max_fields_per_node = 4U << dim;
  } // namespace



  template <int dim>
  void
  GrainFieldLayout<dim>::reinit(TransferCache<dim> &cache,
                                const unsigned int  n_nodes,
                                const MPI_Comm      communicator)
  {
    constexpr unsigned int capacity = max_fields_per_node<dim>;
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    mpi_communicator = communicator;

    // Pass 1: for each node, the list of fields touching it; remember the
    // position of each (particle, vertex) pair in its node's list.
    node_count_scratch.assign(n_nodes, 0U);
    node_field_scratch.resize(std::size_t(n_nodes) * capacity);
    const std::size_t n_particles = cache.n_particles();
    for (std::size_t p = 0; p < n_particles; ++p)
      {
        const unsigned int field = cache.fields[p];
        for (unsigned int v = 0; v < per_particle; ++v)
          {
            const unsigned int node = cache.nodes[p * per_particle + v];
            unsigned int      *list =
              &node_field_scratch[std::size_t(node) * capacity];
            unsigned int &count = node_count_scratch[node];
            unsigned int  k     = 0;
            while (k < count && list[k] != field)
              ++k;
            if (k == count)
              {
                if (count == capacity)
                  throw InputError(
                    "Grains",
                    "more than " + std::to_string(capacity) +
                      " grains meet at one grid node; the grains are too "
                      "small for the grid. Refine the background grid.");
                list[count++] = field;
              }
            cache.slots[p * per_particle + v] = k;
          }
      }

    // Pass 2: number the slots node by node.
    node_slot_offsets.resize(n_nodes + 1);
    node_slot_offsets[0] = 0;
    contact_node_list.clear();
    for (unsigned int node = 0; node < n_nodes; ++node)
      {
        node_slot_offsets[node + 1] =
          node_slot_offsets[node] + node_count_scratch[node];
        if (node_count_scratch[node] > 1)
          contact_node_list.push_back(node);
      }
    const unsigned int n_slots_total = node_slot_offsets[n_nodes];
    slot_nodes.resize(n_slots_total);
    slot_fields.resize(n_slots_total);
    for (unsigned int node = 0; node < n_nodes; ++node)
      for (unsigned int k = 0; k < node_count_scratch[node]; ++k)
        {
          slot_nodes[node_slot_offsets[node] + k] = node;
          slot_fields[node_slot_offsets[node] + k] =
            node_field_scratch[std::size_t(node) * capacity + k];
        }

    // Pass 3: local position -> slot number.
    for (std::size_t p = 0; p < n_particles; ++p)
      for (unsigned int v = 0; v < per_particle; ++v)
        cache.slots[p * per_particle + v] +=
          node_slot_offsets[cache.nodes[p * per_particle + v]];
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::reinit_vector(
    LinearAlgebra::distributed::Vector<double> &vector,
    const unsigned int                          components) const
  {
    // Each rank owns the slots of its nodes. Ghost slots (slots at ghost
    // nodes owned by another rank) arrive with the MPI version.
    const types::global_dof_index n_local =
      types::global_dof_index(n_slots()) * components;
    if (vector.locally_owned_size() != n_local)
      {
        IndexSet owned(Utilities::MPI::sum(n_local, mpi_communicator));
        types::global_dof_index first = 0;
        MPI_Exscan(
          &n_local,
          &first,
          1,
          Utilities::MPI::mpi_type_id_for_type<types::global_dof_index>,
          MPI_SUM,
          mpi_communicator);
        if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          first = 0;
        owned.add_range(first, first + n_local);
        vector.reinit(owned, mpi_communicator);
      }
    else
      vector = 0.;
  }



  template class GrainFieldLayout<2>;
  template class GrainFieldLayout<3>;
} // namespace grainmpm
