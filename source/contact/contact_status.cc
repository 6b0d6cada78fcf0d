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
    slot_kept.assign(n_slots, 0.);
    slot_changes.assign(n_slots, Changes());
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
    wall_kept.assign(wall_slots.size(), 0.);
    wall_changes.assign(wall_slots.size(), Changes());
    any_active = false;
    decided    = false;
  }



  template <int dim>
  bool
  ContactStatus<dim>::settle(const ContactState    before,
                             const Tensor<1, dim> &before_direction,
                             const bool            only_relax,
                             ContactState         &state,
                             Tensor<1, dim>       &direction,
                             Changes              &changes)
  {
    // A primal-dual active set may cycle: a slot caught at one iterate is
    // released at the next and caught again. After max_contact_changes
    // catches and releases in a step (or for every entry with
    // @p only_relax) a free entry is not caught again (it may close its gap
    // a little beyond the bound, which the next step's gap sees); after
    // max_slip_changes changes of friction a sticking one does not slip
    // again. A held entry may always be released or stick. Neither a free
    // entry nor a sticking one can do work against the motion that a
    // constraint resists; friction along a stale slip direction could.
    const bool catch_settled =
      only_relax || changes.contact >= max_contact_changes;
    const bool slip_settled = only_relax || changes.slip >= max_slip_changes;
    const auto count        = [](unsigned char &n) {
      n = static_cast<unsigned char>(std::min(n + 1, 255));
    };
    if (state == before)
      {
        // A sliding entry keeps its slip direction while the new one is
        // within 30 degrees of it (the friction force then still takes at
        // least 0.87 of its bound against the slip); a larger turn counts
        // as a change, and a settled entry whose slip turns sticks.
        const bool turns = state == ContactState::sliding &&
                           (direction - before_direction).norm_square() > 0. &&
                           direction * before_direction < 0.866;
        if (!turns)
          direction = before_direction;
        else if (!slip_settled)
          count(changes.slip);
        else
          {
            state     = ContactState::sticking;
            direction = Tensor<1, dim>();
          }
        return false;
      }
    if (before == ContactState::free)
      {
        // A catch.
        if (catch_settled)
          {
            state     = ContactState::free;
            direction = Tensor<1, dim>();
            return true;
          }
        count(changes.contact);
        return false;
      }
    if (state == ContactState::free)
      {
        // A release.
        count(changes.contact);
        return false;
      }
    // Between sticking and sliding.
    if (state == ContactState::sliding && slip_settled)
      {
        state     = before;
        direction = Tensor<1, dim>();
        return true;
      }
    count(changes.slip);
    return false;
  }



  template <int dim>
  void
  ContactStatus<dim>::freeze(const GrainContact<dim>     &contact,
                             const GrainFieldLayout<dim> &layout,
                             const VectorType            &masses,
                             const VectorType            &normals,
                             const VectorType            &velocities,
                             const double                 mass_threshold,
                             const double                 band,
                             const bool                   catches)
  {
    // The status decided before in this step: for the hysteresis, and to
    // settle decisions that would cycle (settle()).
    const bool               had_status = decided;
    const bool               hysteresis = band > 0. && had_status;
    const ContactStatus<dim> previous =
      had_status ? *this : ContactStatus<dim>();

    // Contact: the decisions of the contact law at these velocities.
    std::fill(slot_state.begin(), slot_state.end(), ContactState::free);
    std::fill(slot_kept.begin(), slot_kept.end(), 0.);
    VectorType        projected(velocities);
    ContactLawOptions options     = contact.law_options(mass_threshold, band);
    options.keep_allowed_approach = keep_allowed_approach;
    contact.decide_contact(layout,
                           masses,
                           normals,
                           projected,
                           options,
                           hysteresis ? &previous.slot_state : nullptr,
                           *this);
    if (had_status)
      for (unsigned int s = 0; s < slot_state.size(); ++s)
        if (settle(previous.slot_state[s],
                   previous.slip_directions[s],
                   !catches,
                   slot_state[s],
                   slip_directions[s],
                   slot_changes[s]))
          slot_kept[s] = previous.slot_kept[s];

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
        const double   allowed =
          contact.get_gaps().wall_allowed_approach(s, wall_faces[w]);
        // The wall constrains the normal velocity beyond the part it leaves
        // to the field (GapEstimator::wall_turning_speed()).
        const double turning = ContactLaw<dim>::wall_turning(
          condition, contact.get_gaps().wall_turning_speed(s, wall_faces[w]));
        wall_state[w] =
          ContactLaw<dim>::classify_wall(condition,
                                         normal,
                                         velocity - turning * normal,
                                         wall_slip_directions[w],
                                         allowed,
                                         hysteresis ? previous.wall_state[w] :
                                                      ContactState::free,
                                         hysteresis ? band : 0.,
                                         keep_allowed_approach);
        if (had_status)
          settle(previous.wall_state[w],
                 previous.wall_slip_directions[w],
                 !catches,
                 wall_state[w],
                 wall_slip_directions[w],
                 wall_changes[w]);
        wall_kept[w] =
          ContactLaw<dim>::wall_kept_approach(condition,
                                              wall_state[w],
                                              allowed,
                                              keep_allowed_approach) +
          (wall_state[w] != ContactState::free ? turning : 0.);
        ContactLaw<dim>::apply_state(wall_state[w],
                                     normal,
                                     ContactLaw<dim>::wall_friction(condition),
                                     wall_slip_directions[w],
                                     Tensor<1, dim>(),
                                     velocity,
                                     wall_kept[w]);
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
        view.light_fraction   = contact.light_field_fraction();
        if (map.affine && keep_allowed_approach)
          view.allowed = slot_kept.data() + begin;
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
                                       velocity,
                                       map.affine ? wall_kept[w] : 0.);
          set_slot_vector<dim>(velocity, velocities, s);
          if (impulses != nullptr)
            impulses->add_wall(face, masses.local_element(s), before, velocity);
        }
    return n_active;
  }



  template class ContactStatus<2>;
  template class ContactStatus<3>;
} // namespace grainmpm
