// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_grain_field_layout_h
#define grainmpm_transfer_grain_field_layout_h

#include <grainmpm/base/config.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/partitioner.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <map>
#include <memory>
#include <vector>

namespace grainmpm
{
  /**
   * The compact multi-valued grid field (doc/theory.md). A slot is
   * one (node, field) pair that particles of that field touch; each field
   * (grain) has a velocity only on its slots, so memory is proportional to
   * particles and occupied nodes, never to grains x nodes. Slots are
   * numbered node by node (CSR: node -> its slots), rebuilt every step, and
   * grid quantities live in `LinearAlgebra::distributed::Vector`s with
   * `components` numbers per slot (slot * components + d).
   *
   * A contact node is a node with two or more slots.
   *
   * In parallel, a slot belongs to the rank that owns
   * its node. A rank whose particles touch a node owned by another rank
   * (a ghost node) holds ghost slots there: reinit() sends the fields it
   * has at its ghost nodes to their owners, which add them to their slots,
   * so the owner's slots at a node are the union over all ranks. Local slot
   * numbers are those of a ghosted `LinearAlgebra::distributed::Vector`:
   * owned slots 0 .. n_slots() - 1 node by node, then the ghost slots in
   * the order of their global numbers. Particle-to-grid sums go into owned
   * and ghost slots and are completed by `compress(VectorOperation::add)`;
   * everything that works on slots (velocities, contact, walls) does so on
   * the owned ones; grid-to-particle reads need `update_ghost_values()`.
   */
  template <int dim>
  class GrainFieldLayout
  {
  public:
    /**
     * Build the slots from the (node, field) pairs of @p cache on the nodes
     * of @p grid, exchanging those at ghost nodes with their owners, and
     * write the local slot of every (particle, vertex) pair into
     * `cache.slots`. Collective. Keeps the slots (and `cache.slots`) while
     * no rank's cache entries changed (TransferCache::entries_changed()).
     */
    void
    reinit(TransferCache<dim> &cache, const BackgroundGrid<dim> &grid);

    /** Number of locally owned slots. */
    unsigned int
    n_slots() const
    {
      return n_owned_slots;
    }

    /** Number of owned and ghost slots. */
    unsigned int
    n_local_slots() const
    {
      return slot_nodes.size();
    }

    /** Local node of (owned or ghost) slot @p slot. */
    unsigned int
    node(const unsigned int slot) const
    {
      return slot_nodes[slot];
    }

    /** Field (grain) of slot @p slot. */
    unsigned int
    field(const unsigned int slot) const
    {
      return slot_fields[slot];
    }

    /** First slot of node @p node; its slots are [begin, end). */
    unsigned int
    node_slots_begin(const unsigned int node) const
    {
      return node_slot_offsets[node];
    }

    /** One past the last slot of node @p node. */
    unsigned int
    node_slots_end(const unsigned int node) const
    {
      return node_slot_offsets[node + 1];
    }

    /** Number of locally owned nodes: the nodes whose slots are owned. */
    unsigned int
    n_nodes() const
    {
      return n_owned_nodes;
    }

    /** The communicator of the grid of the last reinit(). */
    MPI_Comm
    get_communicator() const
    {
      return mpi_communicator;
    }

    /**
     * Whether the contact law reads the fill of (owned or ghost) slot
     * @p slot (GapEstimator): a slot of a contact node or of a node on a box
     * face (the walls). Ghost slots count: their node may be a contact node
     * on its owner. Only these slots need the particles' volumes.
     */
    bool
    reads_fill(const unsigned int slot) const
    {
      return fill_read[slot] != 0;
    }

    /** reads_fill() of every local slot, 1 or 0. */
    const unsigned char *
    fill_read_flags() const
    {
      return fill_read.data();
    }

    /** Owned nodes with two or more slots. */
    const std::vector<unsigned int> &
    contact_nodes() const
    {
      return contact_node_list;
    }

    /**
     * Size @p vector for @p components numbers per slot (owned and ghost
     * slots), zeroed, ghosts included. Other numbers than 1 and dim make
     * a partitioner on first use: all ranks call this together then.
     */
    void
    reinit_vector(LinearAlgebra::distributed::Vector<double> &vector,
                  const unsigned int                          components) const;

  private:
    /** A message of reinit(): global node numbers, counts, fields, slots. */
    using Message = std::vector<types::global_dof_index>;

    /**
     * The position of @p field in the scratch list of @p node, appended if
     * new; sets @p overflow if the list is full.
     */
    unsigned int
    find_or_add(const unsigned int node,
                const unsigned int field,
                bool              &overflow);

    /**
     * Send the fields of the ghost nodes to their owners, which add them
     * to their lists; returns what this rank received, by rank.
     */
    std::map<unsigned int, Message>
    exchange_ghost_fields(const BackgroundGrid<dim> &grid, bool &overflow);

    /**
     * Answer the requests @p received with the global numbers of the owned
     * slots asked for (those of this rank start at @p first_slot), and
     * number the ghost slots from the answers: @p ghost_positions maps a
     * field's place in a ghost node's list to its place among the node's
     * slots, @p ghost_slot_numbers are the global numbers of the ghost
     * slots in their local order.
     */
    void
    number_ghost_slots(
      const BackgroundGrid<dim>             &grid,
      const std::map<unsigned int, Message> &received,
      const types::global_dof_index          first_slot,
      std::vector<unsigned int>             &ghost_positions,
      std::vector<types::global_dof_index>  &ghost_slot_numbers);

    /**
     * Keep @p first_slot and @p ghost_slot_numbers and make the vector
     * partitioners with 1 and dim numbers per slot.
     */
    void
    make_partitioners(
      const types::global_dof_index               first_slot,
      const std::vector<types::global_dof_index> &ghost_slot_numbers);

    /**
     * Make the vector partitioner with @p components numbers per slot
     * (collective: all ranks call it together).
     */
    void
    make_partitioner(const unsigned int components) const;

    std::vector<unsigned int> slot_nodes;
    std::vector<unsigned int> slot_fields;
    std::vector<unsigned int> node_slot_offsets;
    std::vector<unsigned int> contact_node_list;
    /** Per local slot, see reads_fill(). */
    std::vector<unsigned char> fill_read;
    unsigned int               n_owned_slots    = 0;
    unsigned int               n_owned_nodes    = 0;
    MPI_Comm                   mpi_communicator = MPI_COMM_SELF;
    /** Whether reinit() has built the slots once. */
    bool has_slots = false;
    /** This rank's first slot and its ghost slots' global numbers. */
    types::global_dof_index              partition_first_slot = 0;
    std::vector<types::global_dof_index> partition_ghost_slots;
    /**
     * The vector partitioners of the current layout, by components (1 and
     * dim made with the layout, others when first asked for).
     */
    mutable std::map<unsigned int,
                     std::shared_ptr<const Utilities::MPI::Partitioner>>
      partitioners;

    /** Scratch: fields seen at each node during reinit (fixed capacity). */
    std::vector<unsigned int> node_field_scratch;
    std::vector<unsigned int> node_count_scratch;
  };



  /**
   * @p destination = @p source, taking the partitioner of @p source. Slot
   * layouts change every step; deal.II's assignment would keep an old
   * partitioner with the same owned range (and other ghosts).
   */
  inline void
  copy_slot_vector(const LinearAlgebra::distributed::Vector<double> &source,
                   LinearAlgebra::distributed::Vector<double> &destination)
  {
    if (destination.get_partitioner() != source.get_partitioner())
      destination.reinit(source.get_partitioner());
    destination = source;
  }



  /** The vector of slot @p slot in a slot vector with dim numbers per slot. */
  template <int dim>
  inline Tensor<1, dim>
  get_slot_vector(const LinearAlgebra::distributed::Vector<double> &vector,
                  const unsigned int                                slot)
  {
    Tensor<1, dim> value;
    for (unsigned int d = 0; d < dim; ++d)
      value[d] = vector.local_element(slot * dim + d);
    return value;
  }



  /** Set the vector of slot @p slot to @p value (dim numbers per slot). */
  template <int dim>
  inline void
  set_slot_vector(const Tensor<1, dim>                       &value,
                  LinearAlgebra::distributed::Vector<double> &vector,
                  const unsigned int                          slot)
  {
    for (unsigned int d = 0; d < dim; ++d)
      vector.local_element(slot * dim + d) = value[d];
  }
} // namespace grainmpm

#endif
