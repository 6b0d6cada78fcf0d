// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/grain_contact.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  template <int dim>
  GrainContact<dim>::GrainContact(
    const ContactParameters                 &parameters,
    const BackgroundGrid<dim>               &grid,
    const RigidGrainMotion<dim>             &rigid_motion,
    const std::vector<bool>                 &field_is_rigid,
    const std::vector<bool>                 &field_keeps_shape,
    const std::vector<GrainInfo<dim>>       &grains,
    const std::vector<GrainParameters<dim>> &grain_parameters)
    : parameters(parameters)
    , grid(grid)
    , rigid_motion(rigid_motion)
    , field_is_rigid(field_is_rigid)
    , gaps(grid,
           rigid_motion,
           field_is_rigid,
           field_keeps_shape,
           grains,
           grain_parameters,
           parameters.gap_check,
           parameters.gap_check && parameters.shape_gap)
  {}



  template <int dim>
  void
  GrainContact<dim>::compute_normals(const GrainFieldLayout<dim> &layout,
                                     const VectorType &mass_gradients,
                                     VectorType       &normals) const
  {
    layout.reinit_vector(normals, dim);
    for (const unsigned int node : layout.contact_nodes())
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int end   = layout.node_slots_end(node);
        Tensor<1, dim>     total;
        for (unsigned int s = begin; s < end; ++s)
          total += get_slot_vector<dim>(mass_gradients, s);
        // At a node of a rigid grain, every field takes the normal of the
        // rigid grain's shape (the first rigid field's, the partner of the
        // contact law): the gradient of its mass points across the
        // staircase of its points wherever its faces are not aligned with
        // the grid, and a grain sliding along it would climb the steps.
        Tensor<1, dim> rigid_normal;
        unsigned int   first_rigid = end;
        for (unsigned int s = begin; s < end; ++s)
          if (field_is_rigid[layout.field(s)])
            {
              first_rigid = s;
              rigid_normal =
                rigid_motion.surface_normal(layout.field(s),
                                            grid.node_position(node));
              break;
            }
        // Elsewhere (and at the nodes of a rigid grain that rotates or
        // deforms) n_g ~ g_g - sum_{k != g} g_k = 2 g_g - total: for two
        // fields the two normals are exactly opposite. With the gap check,
        // a deformable field whose mass gradient is smaller than a rigid
        // partner's takes the rigid grain's normal: a curved grain resting
        // on one node of a flat rigid face would otherwise get a normal
        // that tilts with its displacement and pushes it further away.
        Tensor<1, dim> rigid_gradient;
        if (uses_gaps() && rigid_normal.norm_square() == 0.)
          for (unsigned int s = begin; s < end; ++s)
            if (field_is_rigid[layout.field(s)] &&
                get_slot_vector<dim>(mass_gradients, s).norm() >
                  rigid_gradient.norm())
              rigid_gradient = get_slot_vector<dim>(mass_gradients, s);
        for (unsigned int s = begin; s < end; ++s)
          {
            const bool rigid = field_is_rigid[layout.field(s)];
            if (rigid_normal.norm_square() > 0.)
              {
                const Tensor<1, dim> normal =
                  !rigid ?
                    -rigid_normal :
                  s == first_rigid ?
                    rigid_normal :
                    rigid_motion.surface_normal(layout.field(s),
                                                grid.node_position(node));
                set_slot_vector<dim>(normal, normals, s);
                continue;
              }
            const Tensor<1, dim> gradient =
              get_slot_vector<dim>(mass_gradients, s);
            const Tensor<1, dim> direction =
              !rigid && rigid_gradient.norm() > gradient.norm() ?
                -rigid_gradient :
                2. * gradient - total;
            const double length = direction.norm();
            if (length > 0.)
              set_slot_vector<dim>(direction / length, normals, s);
          }
      }
  }



  template <int dim>
  unsigned int
  GrainContact<dim>::apply_contact(const GrainFieldLayout<dim> &layout,
                                   const VectorType            &masses,
                                   const VectorType            &normals,
                                   VectorType                  &velocities,
                                   std::vector<unsigned char>  *node_in_contact,
                                   ConstraintImpulses<dim>     *impulses) const
  {
    return sweep(layout,
                 masses,
                 normals,
                 velocities,
                 law_options(),
                 nullptr,
                 nullptr,
                 node_in_contact,
                 impulses);
  }



  template <int dim>
  void
  GrainContact<dim>::decide_contact(
    const GrainFieldLayout<dim>     &layout,
    const VectorType                &masses,
    const VectorType                &normals,
    VectorType                      &velocities,
    const ContactLawOptions         &options,
    const std::vector<ContactState> *previous_states,
    ContactStatus<dim>              &status) const
  {
    sweep(layout,
          masses,
          normals,
          velocities,
          options,
          previous_states,
          &status,
          nullptr,
          nullptr);
  }



  template <int dim>
  unsigned int
  GrainContact<dim>::sweep(const GrainFieldLayout<dim>     &layout,
                           const VectorType                &masses,
                           const VectorType                &normals,
                           VectorType                      &velocities,
                           const ContactLawOptions         &options,
                           const std::vector<ContactState> *previous_states,
                           ContactStatus<dim>              *status,
                           std::vector<unsigned char>      *node_in_contact,
                           ConstraintImpulses<dim>         *impulses) const
  {
    ContactNodeFields<dim>      fields(layout);
    std::vector<Tensor<1, dim>> before;
    std::vector<Tensor<1, dim>> node_slips;
    std::vector<ContactState>   node_states;
    std::vector<double>         node_allowed;
    unsigned int                n_corrected = 0;
    for (const unsigned int node : layout.contact_nodes())
      {
        fields.gather(
          layout, field_is_rigid, masses, normals, velocities, node);
        const unsigned int n = fields.n;
        node_states.resize(n);
        node_slips.resize(n);
        node_allowed.assign(n, 0.);
        ContactNode<dim> view = fields.view();
        view.light_fraction   = light_field_fraction();
        if (uses_gaps())
          gaps.node_allowed_approach(fields.begin, view, node_allowed.data());
        view.allowed = node_allowed.data();
        if (impulses != nullptr)
          before = fields.velocities;
        Tensor<1, dim> reference;
        view.reference = &reference;
        if (status != nullptr)
          {
            view.states          = node_states.data();
            view.slip_directions = node_slips.data();
          }
        if (previous_states != nullptr)
          view.previous_states = previous_states->data() + fields.begin;
        const bool corrected = ContactLaw<dim>::project_node(options, view);
        if (status != nullptr)
          for (unsigned int k = 0; k < n; ++k)
            {
              status->slot_state[fields.begin + k]      = node_states[k];
              status->slip_directions[fields.begin + k] = node_slips[k];
              status->references[fields.begin + k]      = reference;
              // The approach a constrained slot keeps (with a contact
              // model: without, deformable material sticks to a rigid
              // body).
              status->slot_kept[fields.begin + k] =
                options.keep_allowed_approach &&
                    options.model != ContactModel::none &&
                    node_states[k] != ContactState::free ?
                  node_allowed[k] :
                  0.;
            }
        if (corrected)
          {
            fields.scatter(velocities);
            if (impulses != nullptr)
              impulses->add_node(
                layout, node, grid.node_position(node), view, before.data());
            if (node_in_contact != nullptr)
              (*node_in_contact)[node] = 1;
            ++n_corrected;
          }
      }
    return n_corrected;
  }



  template <int dim>
  void
  GrainContact<dim>::apply_walls(const GrainFieldLayout<dim> &layout,
                                 VectorType                  &velocities,
                                 const VectorType            *masses,
                                 ConstraintImpulses<dim>     *impulses) const
  {
    Assert(impulses == nullptr || masses != nullptr,
           ExcMessage("Recording impulses needs the masses."));
    for (const unsigned int node : grid.boundary_nodes())
      {
        const unsigned int faces = grid.node_faces(node);
        for (unsigned int s = layout.node_slots_begin(node);
             s < layout.node_slots_end(node);
             ++s)
          {
            if (field_is_rigid[layout.field(s)])
              continue;
            Tensor<1, dim> velocity = get_slot_vector<dim>(velocities, s);
            for (unsigned int face = 0; face < 2 * dim; ++face)
              if (faces & (1U << face))
                {
                  const Tensor<1, dim> before = velocity;
                  ContactLaw<dim>::apply_wall(
                    grid.boundary_condition(face),
                    ContactLaw<dim>::face_normal(face),
                    velocity,
                    gaps.wall_allowed_approach(s, face),
                    gaps.wall_turning_speed(s, face));
                  if (impulses != nullptr)
                    impulses->add_wall(face,
                                       masses->local_element(s),
                                       before,
                                       velocity);
                }
            set_slot_vector<dim>(velocity, velocities, s);
          }
      }
  }



  template class GrainContact<2>;
  template class GrainContact<3>;
} // namespace grainmpm
