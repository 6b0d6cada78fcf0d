// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_implicit_slot_projection_h
#define grainmpm_time_integration_implicit_slot_projection_h

#include <grainmpm/base/config.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>
#include <vector>

namespace grainmpm
{
  /**
   * The linear part P of the frozen contact and wall projection of the
   * implicit residual, row by row over the owned and ghost slots of the
   * layout: (P z)_a = sum_k blocks[k] z_partners[k] for k in
   * [start[a], start[a + 1]), the partners being slots of the node of a
   * (a itself among them). Contact couples the fields of a node through
   * their centre-of-mass (or rigid) reference velocity; walls act on the
   * slot alone. groups[group_start[a] .. group_start[a + 1]) lists the
   * slots of the node of a that this rank knows (all of them at owned
   * nodes): the couplings P may have whatever the contact status.
   *
   * reinit_groups() sets up the groups once per step (they depend on the
   * slots only), probe() the rows for the contact status frozen at
   * present.
   */
  template <int dim>
  class SlotProjection
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;
    /**
     * The linear part of the frozen projection, applied in place to a
     * vector with the layout of the unknowns (owned entries).
     */
    using LinearMap = std::function<void(VectorType &)>;

    /**
     * The groups of the slots of @p layout, the largest number of slots
     * at a node (any rank), and the place of each owned and ghost slot
     * among the slots of its node (its owner's numbering; ghost slots
     * learn it from the owner).
     */
    void
    reinit_groups(const GrainFieldLayout<dim> &layout);

    /**
     * The rows of P (start, partners, blocks) by probing
     * @p linear_projection: its linear part is node-wise, so one probe per
     * place j among the slots of a node and direction d, a unit vector in
     * the j-th slot of every node, gives the columns (j, d) of all node
     * blocks at once. @p unknown says for each owned and ghost slot
     * whether it is an unknown; only unknowns are probed and kept.
     * @p probe is a work vector with the layout of the unknowns.
     */
    void
    probe(const GrainFieldLayout<dim> &layout,
          const std::vector<bool>     &unknown,
          const LinearMap             &linear_projection,
          VectorType                  &probe);

    /** The rows of P: partners and blocks of each slot. */
    std::vector<unsigned int>   start;
    std::vector<unsigned int>   partners;
    std::vector<Tensor<2, dim>> blocks;
    /** The slots of the node of each slot that this rank knows. */
    std::vector<unsigned int> group_start;
    std::vector<unsigned int> groups;

  private:
    /** The largest number of slots at a node (any rank). */
    unsigned int slots_per_node = 0;
    /** The place of each owned and ghost slot among its node's slots. */
    std::vector<unsigned int> slot_places;
  };
} // namespace grainmpm

#endif
