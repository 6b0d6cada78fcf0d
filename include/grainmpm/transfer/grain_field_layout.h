// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_grain_field_layout_h
#define grainmpm_transfer_grain_field_layout_h

#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/partitioner.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  using namespace dealii;

  /**
   * The compact multi-valued grid field of DESIGN.md section 4. A slot is
   * one (node, field) pair that particles of that field touch; each field
   * (grain) has a velocity only on its slots, so memory is proportional to
   * particles and occupied nodes, never to grains x nodes. Slots are
   * numbered node by node (CSR: node -> its slots), rebuilt every step, and
   * grid quantities live in `LinearAlgebra::distributed::Vector`s with
   * `components` numbers per slot (slot * components + d).
   *
   * A contact node is a node with two or more slots.
   */
  template <int dim>
  class GrainFieldLayout
  {
  public:
    /**
     * Build the slots from the (node, field) pairs of @p cache and write the
     * slot of every (particle, vertex) pair into `cache.slots`.
     * @p n_nodes is the number of local nodes.
     */
    void
    reinit(TransferCache<dim> &cache,
           const unsigned int  n_nodes,
           const MPI_Comm      communicator);

    /** Number of slots. */
    unsigned int
    n_slots() const
    {
      return slot_nodes.size();
    }

    /** Node of slot @p slot. */
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

    /** Number of nodes the layout was built for. */
    unsigned int
    n_nodes() const
    {
      return node_slot_offsets.size() - 1;
    }

    /** Nodes with two or more slots. */
    const std::vector<unsigned int> &
    contact_nodes() const
    {
      return contact_node_list;
    }

    /** Size @p vector for @p components numbers per slot, zeroed. */
    void
    reinit_vector(LinearAlgebra::distributed::Vector<double> &vector,
                  const unsigned int                          components) const;

  private:
    std::vector<unsigned int> slot_nodes;
    std::vector<unsigned int> slot_fields;
    std::vector<unsigned int> node_slot_offsets;
    std::vector<unsigned int> contact_node_list;
    MPI_Comm                  mpi_communicator = MPI_COMM_SELF;

    /** Scratch: fields seen at each node during reinit (fixed capacity). */
    std::vector<unsigned int> node_field_scratch;
    std::vector<unsigned int> node_count_scratch;
  };



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
