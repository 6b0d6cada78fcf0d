// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/contact_node_fields.h>

#include <algorithm>

namespace grainmpm
{
  template <int dim>
  ContactNodeFields<dim>::ContactNodeFields(const GrainFieldLayout<dim> &layout)
  {
    unsigned int capacity = 0;
    for (const unsigned int node : layout.contact_nodes())
      capacity =
        std::max(capacity,
                 layout.node_slots_end(node) - layout.node_slots_begin(node));
    rigid.reset(new bool[capacity]);
  }



  template <int dim>
  void
  ContactNodeFields<dim>::gather(const GrainFieldLayout<dim> &layout,
                                 const std::vector<bool>     &field_is_rigid,
                                 const VectorType            &slot_masses,
                                 const VectorType            &slot_normals,
                                 const VectorType            &slot_velocities,
                                 const unsigned int           node)
  {
    begin = layout.node_slots_begin(node);
    n     = layout.node_slots_end(node) - begin;
    masses.resize(n);
    normals.resize(n);
    velocities.resize(n);
    for (unsigned int k = 0; k < n; ++k)
      {
        masses[k]     = slot_masses.local_element(begin + k);
        rigid[k]      = field_is_rigid[layout.field(begin + k)];
        normals[k]    = get_slot_vector<dim>(slot_normals, begin + k);
        velocities[k] = get_slot_vector<dim>(slot_velocities, begin + k);
      }
  }



  template <int dim>
  void
  ContactNodeFields<dim>::scatter(VectorType &slot_velocities) const
  {
    for (unsigned int k = 0; k < n; ++k)
      set_slot_vector<dim>(velocities[k], slot_velocities, begin + k);
  }



  template class ContactNodeFields<2>;
  template class ContactNodeFields<3>;
} // namespace grainmpm
