// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_contact_node_fields_h
#define grainmpm_contact_contact_node_fields_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  /**
   * The fields of one contact node copied from the slot vectors into
   * contiguous arrays, for the contact law at the node (view()), and the
   * corrected velocities copied back.
   */
  template <int dim>
  class ContactNodeFields
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /** Room for the largest contact node of @p layout. */
    explicit ContactNodeFields(const GrainFieldLayout<dim> &layout);

    /**
     * Copy the masses, rigid flags (from @p field_is_rigid), normals and
     * velocities of the slots of @p node.
     */
    void
    gather(const GrainFieldLayout<dim> &layout,
           const std::vector<bool>     &field_is_rigid,
           const VectorType            &slot_masses,
           const VectorType            &slot_normals,
           const VectorType            &slot_velocities,
           const unsigned int           node);

    /** Copy the velocities back into @p slot_velocities. */
    void
    scatter(VectorType &slot_velocities) const;

    /** The node gathered last, without the optional members. */
    ContactNode<dim>
    view()
    {
      ContactNode<dim> node;
      node.n          = n;
      node.masses     = masses.data();
      node.rigid      = rigid.get();
      node.normals    = normals.data();
      node.velocities = velocities.data();
      return node;
    }

    /** The first slot of the node, and the number of its slots. */
    unsigned int begin = 0;
    unsigned int n     = 0;
    /** The copies. */
    std::vector<double>         masses;
    std::vector<Tensor<1, dim>> normals;
    std::vector<Tensor<1, dim>> velocities;
    /** (std::vector<bool> has no data().) */
    std::unique_ptr<bool[]> rigid;
  };
} // namespace grainmpm

#endif
