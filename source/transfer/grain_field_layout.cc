// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/mpi_tools.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/mpi.h>

#include <algorithm>

namespace grainmpm
{
  namespace
  {
    // Fields a node can hold. A node's weights reach into 2^dim cells (4^dim
    // with GIMP, partly); with a few grains per cell 4 * 2^dim is far above
    // what packings produce.
    template <int dim>
    constexpr unsigned int max_fields_per_node = 4U << dim;
  } // namespace



  template <int dim>
  inline unsigned int
  GrainFieldLayout<dim>::find_or_add(const unsigned int node,
                                     const unsigned int field,
                                     bool              &overflow)
  {
    constexpr unsigned int capacity = max_fields_per_node<dim>;
    unsigned int *list  = &node_field_scratch[std::size_t(node) * capacity];
    unsigned int &count = node_count_scratch[node];
    unsigned int  k     = 0;
    while (k < count && list[k] != field)
      ++k;
    if (k == count)
      {
        if (count == capacity)
          {
            overflow = true;
            return 0U;
          }
        list[count++] = field;
      }
    return k;
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::reinit(TransferCache<dim>        &cache,
                                const BackgroundGrid<dim> &grid)
  {
    constexpr unsigned int capacity = max_fields_per_node<dim>;
    const unsigned int     n_nodes  = grid.n_nodes();
    n_owned_nodes                   = grid.n_owned_nodes();
    mpi_communicator = grid.get_triangulation().get_communicator();

    // The slots are a function of the cache's entries (their nodes, the
    // particles' fields) on all ranks: keep them, and the partitioners,
    // while no rank's entries changed. One collective instead of the
    // exchanges below, which cost some 30 collective calls per step.
    if (has_slots && Utilities::MPI::max(cache.entries_changed() ? 1U : 0U,
                                         mpi_communicator) == 0)
      return;
    has_slots = true;

    // Pass 1: for each node, the list of fields touching it; remember the
    // position of each (particle, vertex) pair in its node's list.
    bool overflow = false;
    node_count_scratch.assign(n_nodes, 0U);
    node_field_scratch.resize(std::size_t(n_nodes) * capacity);
    const std::size_t n_particles = cache.n_particles();
    for (std::size_t p = 0; p < n_particles; ++p)
      for (unsigned int e = cache.first_entry[p]; e < cache.first_entry[p + 1];
           ++e)
        cache.slots[e] = find_or_add(cache.nodes[e], cache.fields[p], overflow);

    // Pass 2: the owners of ghost nodes add the fields other ranks have
    // there.
    const std::map<unsigned int, Message> received =
      exchange_ghost_fields(grid, overflow);
    if (Utilities::MPI::max(overflow ? 1U : 0U, mpi_communicator) > 0)
      throw InputError("Grains",
                       "more than " + std::to_string(capacity) +
                         " grains meet at one grid node; the grains are too "
                         "small for the grid. Refine the background grid.");

    // Pass 3: number the owned slots node by node.
    node_slot_offsets.resize(n_nodes + 1);
    node_slot_offsets[0] = 0;
    contact_node_list.clear();
    for (unsigned int node = 0; node < n_owned_nodes; ++node)
      {
        node_slot_offsets[node + 1] =
          node_slot_offsets[node] + node_count_scratch[node];
        if (node_count_scratch[node] > 1)
          contact_node_list.push_back(node);
      }
    n_owned_slots                         = node_slot_offsets[n_owned_nodes];
    const types::global_dof_index n_owned = n_owned_slots;
    const types::global_dof_index first_slot =
      sum_over_lower_ranks(n_owned, mpi_communicator);

    // Passes 4 and 5: the ghost slots and their global numbers.
    std::vector<unsigned int>            ghost_positions;
    std::vector<types::global_dof_index> ghost_slot_numbers;
    number_ghost_slots(
      grid, received, first_slot, ghost_positions, ghost_slot_numbers);

    const unsigned int n_local = node_slot_offsets[n_nodes];
    slot_nodes.resize(n_local);
    slot_fields.resize(n_local);
    fill_read.resize(n_local);
    for (unsigned int node = 0; node < n_nodes; ++node)
      for (unsigned int k = 0; k < node_count_scratch[node]; ++k)
        {
          // (See reads_fill().)
          fill_read[node_slot_offsets[node] + k] =
            node >= n_owned_nodes || node_count_scratch[node] > 1 ||
            grid.node_faces(node) != 0;
          const unsigned int j =
            node < n_owned_nodes ?
              k :
              ghost_positions[std::size_t(node - n_owned_nodes) * capacity + k];
          slot_nodes[node_slot_offsets[node] + j] = node;
          slot_fields[node_slot_offsets[node] + j] =
            node_field_scratch[std::size_t(node) * capacity + k];
        }

    // Pass 6: local position -> slot number.
    for (std::size_t e = 0; e < cache.n_entries(); ++e)
      {
        const unsigned int node = cache.nodes[e];
        unsigned int      &slot = cache.slots[e];
        slot                    = node_slot_offsets[node] +
               (node < n_owned_nodes ?
                  slot :
                  ghost_positions[std::size_t(node - n_owned_nodes) * capacity +
                                  slot]);
      }

    make_partitioners(first_slot, ghost_slot_numbers);
  }



  template <int dim>
  std::map<unsigned int, typename GrainFieldLayout<dim>::Message>
  GrainFieldLayout<dim>::exchange_ghost_fields(const BackgroundGrid<dim> &grid,
                                               bool &overflow)
  {
    constexpr unsigned int             capacity = max_fields_per_node<dim>;
    const Utilities::MPI::Partitioner &nodes    = *grid.node_partitioner();
    // [node, count, fields...] per ghost node with fields, to its owner.
    std::map<unsigned int, Message> requests;
    unsigned int                    ghost = n_owned_nodes;
    for (const auto &[rank, n_ghosts] : nodes.ghost_targets())
      for (unsigned int i = 0; i < n_ghosts; ++i, ++ghost)
        if (node_count_scratch[ghost] > 0)
          {
            Message &message = requests[rank];
            message.push_back(grid.node_global_index(ghost));
            message.push_back(node_count_scratch[ghost]);
            for (unsigned int k = 0; k < node_count_scratch[ghost]; ++k)
              message.push_back(
                node_field_scratch[std::size_t(ghost) * capacity + k]);
          }
    std::map<unsigned int, Message> received =
      Utilities::MPI::some_to_some(mpi_communicator, requests);
    for (const auto &[rank, message] : received)
      for (std::size_t i = 0; i < message.size(); i += 2 + message[i + 1])
        {
          const unsigned int node = nodes.global_to_local(message[i]);
          for (unsigned int k = 0; k < message[i + 1]; ++k)
            find_or_add(node, message[i + 2 + k], overflow);
        }
    return received;
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::number_ghost_slots(
    const BackgroundGrid<dim>             &grid,
    const std::map<unsigned int, Message> &received,
    const types::global_dof_index          first_slot,
    std::vector<unsigned int>             &ghost_positions,
    std::vector<types::global_dof_index>  &ghost_slot_numbers)
  {
    constexpr unsigned int             capacity = max_fields_per_node<dim>;
    const Utilities::MPI::Partitioner &nodes    = *grid.node_partitioner();
    bool                               overflow = false; // checked before

    // Pass 4: the owners answer with the global numbers of the requested
    // slots, in the order asked.
    std::map<unsigned int, Message> answers;
    for (const auto &[rank, message] : received)
      {
        Message &answer = answers[rank];
        for (std::size_t i = 0; i < message.size(); i += 2 + message[i + 1])
          {
            const unsigned int node = nodes.global_to_local(message[i]);
            for (unsigned int k = 0; k < message[i + 1]; ++k)
              answer.push_back(first_slot + node_slot_offsets[node] +
                               find_or_add(node, message[i + 2 + k], overflow));
          }
      }
    const std::map<unsigned int, Message> replies =
      Utilities::MPI::some_to_some(mpi_communicator, answers);

    // Pass 5: the ghost slots, node by node (ghost nodes are in the order of
    // their global DoF, so of their owner and the owner's node numbering),
    // each node's in the order of their global numbers: then the local
    // ghost slots are in the order of their global numbers, which is the
    // order of a vector partitioner's ghost entries. ghost_positions maps
    // a field's place in a ghost node's list to its place among the
    // node's slots.
    const unsigned int n_ghost_nodes = grid.n_nodes() - n_owned_nodes;
    ghost_positions.assign(std::size_t(n_ghost_nodes) * capacity, 0U);
    ghost_slot_numbers.clear();
    std::vector<std::pair<types::global_dof_index, unsigned int>> order;
    unsigned int ghost = n_owned_nodes;
    for (const auto &[rank, n_ghosts] : nodes.ghost_targets())
      {
        const auto  reply    = replies.find(rank);
        std::size_t position = 0;
        for (unsigned int i = 0; i < n_ghosts; ++i, ++ghost)
          {
            const unsigned int count     = node_count_scratch[ghost];
            node_slot_offsets[ghost + 1] = node_slot_offsets[ghost] + count;
            if (count == 0)
              continue;
            Assert(reply != replies.end() &&
                     position + count <= reply->second.size(),
                   ExcInternalError());
            order.clear();
            for (unsigned int k = 0; k < count; ++k)
              order.emplace_back(reply->second[position++], k);
            std::sort(order.begin(), order.end());
            for (unsigned int j = 0; j < count; ++j)
              {
                ghost_positions[std::size_t(ghost - n_owned_nodes) * capacity +
                                order[j].second] = j;
                AssertThrow(ghost_slot_numbers.empty() ||
                              order[j].first > ghost_slot_numbers.back(),
                            ExcInternalError());
                ghost_slot_numbers.push_back(order[j].first);
              }
          }
      }
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::make_partitioners(
    const types::global_dof_index               first_slot,
    const std::vector<types::global_dof_index> &ghost_slot_numbers)
  {
    // Built by all ranks together (their construction communicates).
    partitioners.clear();
    partition_first_slot  = first_slot;
    partition_ghost_slots = ghost_slot_numbers;
    make_partitioner(1);
    make_partitioner(dim);
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::make_partitioner(const unsigned int components) const
  {
    const types::global_dof_index n_owned = n_owned_slots;
    const types::global_dof_index n_total =
      Utilities::MPI::sum(n_owned, mpi_communicator);
    IndexSet owned(n_total * components);
    owned.add_range(partition_first_slot * components,
                    (partition_first_slot + n_owned) * components);
    IndexSet                             ghosts(n_total * components);
    std::vector<types::global_dof_index> indices;
    indices.reserve(partition_ghost_slots.size() * components);
    for (const types::global_dof_index slot : partition_ghost_slots)
      for (unsigned int d = 0; d < components; ++d)
        indices.push_back(slot * components + d);
    ghosts.add_indices(indices.begin(), indices.end());
    partitioners[components] =
      std::make_shared<Utilities::MPI::Partitioner>(owned,
                                                    ghosts,
                                                    mpi_communicator);
  }



  template <int dim>
  void
  GrainFieldLayout<dim>::reinit_vector(
    LinearAlgebra::distributed::Vector<double> &vector,
    const unsigned int                          components) const
  {
    auto partitioner = partitioners.find(components);
    if (partitioner == partitioners.end())
      {
        make_partitioner(components);
        partitioner = partitioners.find(components);
      }
    if (vector.get_partitioner() != partitioner->second)
      vector.reinit(partitioner->second);
    else
      vector = 0.;
  }



  template class GrainFieldLayout<2>;
  template class GrainFieldLayout<3>;
} // namespace grainmpm
