// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/contact_node_fields.h>
#include <grainmpm/contact/contact_status.h>
#include <grainmpm/contact/grain_contact.h>

#include <algorithm>

namespace grainmpm
{
  template <int dim>
  void
  ContactStatus<dim>::reinit(const GrainContact<dim>     &contact,
                             const GrainFieldLayout<dim> &layout)
  {
    const BackgroundGrid<dim> &grid           = contact.get_grid();
    const std::vector<bool>   &field_is_rigid = contact.get_field_is_rigid();
    const unsigned int         n_slots        = layout.n_slots();
    slot_state.assign(n_slots, ContactState::free);
    slip_directions.assign(n_slots, Tensor<1, dim>());
    references.assign(n_slots, Tensor<1, dim>());
    wall_slots.clear();
    wall_faces.clear();
    for (const unsigned int node : grid.boundary_nodes())
      {
        const unsigned int faces = grid.node_faces(node);
        for (unsigned int s = layout.node_slots_begin(node);
             s < layout.node_slots_end(node);
             ++s)
          if (!field_is_rigid[layout.field(s)])
            for (unsigned int face = 0; face < 2 * dim; ++face)
              if ((faces & (1U << face)) &&
                  grid.boundary_condition(face).type != BoundaryType::open)
                {
                  wall_slots.push_back(s);
                  wall_faces.push_back(face);
                }
      }
    wall_state.assign(wall_slots.size(), ContactState::free);
    wall_slip_directions.assign(wall_slots.size(), Tensor<1, dim>());
    any_active = false;
    decided    = false;
  }



  template <int dim>
  void
  ContactStatus<dim>::freeze(const GrainContact<dim>     &contact,
                             const GrainFieldLayout<dim> &layout,
                             const VectorType            &masses,
                             const VectorType            &normals,
                             const VectorType            &velocities,
                             const double                 mass_threshold,
                             const double                 band)
  {
    // The states decided before, for the hysteresis.
    const bool                hysteresis = band > 0. && decided;
    std::vector<ContactState> previous_slots, previous_walls;
    if (hysteresis)
      {
        previous_slots = slot_state;
        previous_walls = wall_state;
      }

    // Contact: the decisions of the contact law at these velocities.
    std::fill(slot_state.begin(), slot_state.end(), ContactState::free);
    VectorType projected(velocities);
    contact.decide_contact(layout,
                           masses,
                           normals,
                           projected,
                           contact.law_options(mass_threshold, band),
                           hysteresis ? &previous_slots : nullptr,
                           *this);

    // Walls see the velocities after contact, face after face.
    const BackgroundGrid<dim> &grid = contact.get_grid();
    for (unsigned int w = 0; w < wall_slots.size(); ++w)
      {
        const unsigned int       s = wall_slots[w];
        const BoundaryCondition &condition =
          grid.boundary_condition(wall_faces[w]);
        const Tensor<1, dim> normal =
          ContactLaw<dim>::face_normal(wall_faces[w]);
        Tensor<1, dim> velocity = get_slot_vector<dim>(projected, s);
        wall_state[w]           = ContactLaw<dim>::classify_wall(
          condition,
          normal,
          velocity,
          wall_slip_directions[w],
          contact.get_gaps().wall_allowed_approach(s, wall_faces[w]),
          hysteresis ? previous_walls[w] : ContactState::free,
          hysteresis ? band : 0.);
        ContactLaw<dim>::apply_state(wall_state[w],
                                     normal,
                                     ContactLaw<dim>::wall_friction(condition),
                                     wall_slip_directions[w],
                                     Tensor<1, dim>(),
                                     velocity);
        set_slot_vector<dim>(velocity, projected, s);
      }
    const auto active = [](const ContactState state) {
      return state != ContactState::free;
    };
    decided    = true;
    any_active = std::any_of(slot_state.begin(), slot_state.end(), active) ||
                 std::any_of(wall_state.begin(), wall_state.end(), active);
  }



  template <int dim>
  unsigned int
  ContactStatus<dim>::apply(const GrainContact<dim>     &contact,
                            const GrainFieldLayout<dim> &layout,
                            const VectorType            &masses,
                            const VectorType            &normals,
                            VectorType                  &velocities,
                            std::vector<unsigned char>  *node_in_contact,
                            ConstraintImpulses<dim>     *impulses) const
  {
    return apply_map({true, false, true},
                     contact,
                     layout,
                     masses,
                     normals,
                     velocities,
                     node_in_contact,
                     impulses);
  }



  template <int dim>
  unsigned int
  ContactStatus<dim>::apply_simplified(const GrainContact<dim>     &contact,
                                       const GrainFieldLayout<dim> &layout,
                                       const VectorType            &masses,
                                       const VectorType            &normals,
                                       VectorType &velocities) const
  {
    return apply_map({true, true, true},
                     contact,
                     layout,
                     masses,
                     normals,
                     velocities,
                     nullptr,
                     nullptr);
  }



  template <int dim>
  void
  ContactStatus<dim>::apply_simplified_linear_part(
    const GrainContact<dim>     &contact,
    const GrainFieldLayout<dim> &layout,
    const VectorType            &masses,
    const VectorType            &normals,
    VectorType                  &differences) const
  {
    apply_map({false, true, true},
              contact,
              layout,
              masses,
              normals,
              differences,
              nullptr,
              nullptr);
  }



  template <int dim>
  void
  ContactStatus<dim>::apply_symmetric_linear_part(
    const GrainContact<dim>     &contact,
    const GrainFieldLayout<dim> &layout,
    const VectorType            &masses,
    const VectorType            &normals,
    VectorType                  &velocities) const
  {
    apply_map({false, false, false},
              contact,
              layout,
              masses,
              normals,
              velocities,
              nullptr,
              nullptr);
  }



  template <int dim>
  unsigned int
  ContactStatus<dim>::apply_map(const Map                   &map,
                                const GrainContact<dim>     &contact,
                                const GrainFieldLayout<dim> &layout,
                                const VectorType            &masses,
                                const VectorType            &normals,
                                VectorType                  &velocities,
                                std::vector<unsigned char>  *node_flags,
                                ConstraintImpulses<dim>     *impulses) const
  {
    if (!any_active)
      return 0;
    const BackgroundGrid<dim> &grid = contact.get_grid();
    const double mu = map.friction ? contact.law_options().friction() : 0.;
    // v_ref: from the velocities, frozen, or zero in the linear part of
    // the map with v_ref frozen.
    const Tensor<1, dim>        zero;
    ContactNodeFields<dim>      fields(layout);
    std::vector<Tensor<1, dim>> before;
    unsigned int                n_active = 0;
    for (const unsigned int node : layout.contact_nodes())
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int end   = layout.node_slots_end(node);
        bool               any   = false;
        for (unsigned int s = begin; s < end; ++s)
          any = any || (slot_state[s] != ContactState::free);
        if (!any)
          continue;
        ++n_active;
        if (node_flags != nullptr)
          (*node_flags)[node] = 1;
        fields.gather(layout,
                      contact.get_field_is_rigid(),
                      masses,
                      normals,
                      velocities,
                      node);
        if (impulses != nullptr)
          before = fields.velocities;
        ContactNode<dim> view = fields.view();
        ContactLaw<dim>::project_node_frozen(view,
                                             slot_state.data() + begin,
                                             slip_directions.data() + begin,
                                             mu,
                                             !map.frozen_reference ? nullptr :
                                             map.affine ? &references[begin] :
                                                          &zero);
        fields.scatter(velocities);
        if (impulses != nullptr)
          impulses->add_node(
            layout, node, grid.node_position(node), view, before.data());
      }

    for (unsigned int w = 0; w < wall_slots.size(); ++w)
      if (wall_state[w] != ContactState::free)
        {
          const unsigned int   s        = wall_slots[w];
          const unsigned int   face     = wall_faces[w];
          Tensor<1, dim>       velocity = get_slot_vector<dim>(velocities, s);
          const Tensor<1, dim> before   = velocity;
          ContactLaw<dim>::apply_state(wall_state[w],
                                       ContactLaw<dim>::face_normal(face),
                                       map.friction ?
                                         ContactLaw<dim>::wall_friction(
                                           grid.boundary_condition(face)) :
                                         0.,
                                       wall_slip_directions[w],
                                       Tensor<1, dim>(),
                                       velocity);
          set_slot_vector<dim>(velocity, velocities, s);
          if (impulses != nullptr)
            impulses->add_wall(face, masses.local_element(s), before, velocity);
        }
    return n_active;
  }



  template class ContactStatus<2>;
  template class ContactStatus<3>;
} // namespace grainmpm
