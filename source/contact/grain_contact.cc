// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/grain_contact.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  template <int dim>
  GrainContact<dim>::GrainContact(const ContactParameters           &parameters,
                                  const BackgroundGrid<dim>         &grid,
                                  const std::vector<GrainInfo<dim>> &grains,
                                  const std::vector<bool> &field_is_rigid)
    : parameters(parameters)
    , grid(grid)
    , grains(grains)
    , field_is_rigid(field_is_rigid)
    , has_rigid_fields(std::find(field_is_rigid.begin(),
                                 field_is_rigid.end(),
                                 true) != field_is_rigid.end())
    , gaps(grid, parameters.gap_check)
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
        // n_g ~ g_g - sum_{k != g} g_k = 2 g_g - total: for two fields the
        // two normals are exactly opposite.
        for (unsigned int s = begin; s < end; ++s)
          {
            const Tensor<1, dim> direction =
              2. * get_slot_vector<dim>(mass_gradients, s) - total;
            const double length = direction.norm();
            if (length > 0.)
              set_slot_vector<dim>(direction / length, normals, s);
          }
      }
  }



  template <int dim>
  void
  GrainContact<dim>::prescribe_rigid_velocities(
    const GrainFieldLayout<dim> &layout,
    VectorType                  &velocities,
    const double                 time) const
  {
    if (!has_rigid_fields)
      return;
    Vector<double> value(dim);
    for (unsigned int slot = 0; slot < layout.n_slots(); ++slot)
      {
        const unsigned int field = layout.field(slot);
        if (!field_is_rigid[field])
          continue;
        FunctionParser<dim> &function = *grains[field].prescribed_velocity;
        function.set_time(time);
        function.vector_value(grid.node_position(layout.node(slot)), value);
        for (unsigned int d = 0; d < dim; ++d)
          velocities.local_element(slot * dim + d) = value[d];
      }
  }



  template <int dim>
  unsigned int
  GrainContact<dim>::apply_contact(
    const GrainFieldLayout<dim>     &layout,
    const VectorType                &masses,
    const VectorType                &normals,
    VectorType                      &velocities,
    std::vector<unsigned char>      *node_in_contact,
    const double                     mass_threshold,
    ContactStatus<dim>              *status,
    ConstraintImpulses<dim>         *impulses,
    const std::vector<ContactState> *previous_states,
    const double                     band) const
  {
    ContactLawOptions options;
    options.model                = parameters.model;
    options.friction_coefficient = parameters.friction_coefficient;
    options.mass_threshold       = mass_threshold;
    options.band                 = band;
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
              status->allowed[fields.begin + k]         = node_allowed[k];
            }
        if (corrected)
          {
            fields.scatter(velocities);
            if (impulses != nullptr)
              record_impulses(layout,
                              node,
                              n,
                              fields.masses.data(),
                              fields.rigid.get(),
                              fields.normals.data(),
                              before.data(),
                              fields.velocities.data(),
                              *impulses);
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
                    gaps.wall_allowed_approach(s, face));
                  if (impulses != nullptr)
                    impulses->walls[face] += impulses->scale *
                                             masses->local_element(s) *
                                             (velocity - before);
                }
            set_slot_vector<dim>(velocity, velocities, s);
          }
      }
  }



  template <int dim>
  void
  GrainContact<dim>::reinit_status(const GrainFieldLayout<dim> &layout,
                                   ContactStatus<dim>          &status) const
  {
    const unsigned int n_slots = layout.n_slots();
    status.slot_state.assign(n_slots, ContactState::free);
    status.slip_directions.assign(n_slots, Tensor<1, dim>());
    status.references.assign(n_slots, Tensor<1, dim>());
    status.allowed.assign(n_slots, 0.);
    status.wall_slots.clear();
    status.wall_faces.clear();
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
                  status.wall_slots.push_back(s);
                  status.wall_faces.push_back(face);
                }
      }
    status.wall_state.assign(status.wall_slots.size(), ContactState::free);
    status.wall_slip_directions.assign(status.wall_slots.size(),
                                       Tensor<1, dim>());
    status.wall_allowed.assign(status.wall_slots.size(), 0.);
    status.any_active = false;
    status.decided    = false;
  }



  template <int dim>
  void
  GrainContact<dim>::freeze(const GrainFieldLayout<dim> &layout,
                            const VectorType            &masses,
                            const VectorType            &normals,
                            const VectorType            &velocities,
                            const double                 mass_threshold,
                            ContactStatus<dim>          &status,
                            const double                 band) const
  {
    // The states decided before, for the hysteresis.
    const bool                hysteresis = band > 0. && status.decided;
    std::vector<ContactState> previous_slots, previous_walls;
    if (hysteresis)
      {
        previous_slots = status.slot_state;
        previous_walls = status.wall_state;
      }

    // Contact: the decisions of the contact law at these velocities.
    std::fill(status.slot_state.begin(),
              status.slot_state.end(),
              ContactState::free);
    VectorType projected(velocities);
    apply_contact(layout,
                  masses,
                  normals,
                  projected,
                  nullptr,
                  mass_threshold,
                  &status,
                  nullptr,
                  hysteresis ? &previous_slots : nullptr,
                  band);

    // Walls see the velocities after contact, face after face.
    for (unsigned int w = 0; w < status.wall_slots.size(); ++w)
      {
        const unsigned int       s = status.wall_slots[w];
        const BoundaryCondition &condition =
          grid.boundary_condition(status.wall_faces[w]);
        const Tensor<1, dim> normal =
          ContactLaw<dim>::face_normal(status.wall_faces[w]);
        Tensor<1, dim> velocity = get_slot_vector<dim>(projected, s);
        status.wall_allowed[w] =
          condition.type == BoundaryType::no_slip ?
            0. :
            gaps.wall_allowed_approach(s, status.wall_faces[w]);
        status.wall_state[w] =
          ContactLaw<dim>::classify_wall(condition,
                                         normal,
                                         velocity,
                                         status.wall_slip_directions[w],
                                         status.wall_allowed[w],
                                         hysteresis ? previous_walls[w] :
                                                      ContactState::free,
                                         hysteresis ? band : 0.);
        ContactLaw<dim>::apply_state(status.wall_state[w],
                                     normal,
                                     ContactLaw<dim>::wall_friction(condition),
                                     status.wall_slip_directions[w],
                                     Tensor<1, dim>(),
                                     velocity,
                                     status.wall_allowed[w]);
        set_slot_vector<dim>(velocity, projected, s);
      }
    const auto active = [](const ContactState state) {
      return state != ContactState::free;
    };
    status.decided = true;
    status.any_active =
      std::any_of(status.slot_state.begin(), status.slot_state.end(), active) ||
      std::any_of(status.wall_state.begin(), status.wall_state.end(), active);
  }



  template <int dim>
  unsigned int
  GrainContact<dim>::apply_frozen(const GrainFieldLayout<dim> &layout,
                                  const VectorType            &masses,
                                  const VectorType            &normals,
                                  const ContactStatus<dim>    &status,
                                  const Reference              reference,
                                  VectorType                  &velocities,
                                  std::vector<unsigned char>  *node_flags,
                                  ConstraintImpulses<dim>     *impulses) const
  {
    if (!status.any_active)
      return 0;
    // The preconditioner's linear part leaves out the friction of sliding
    // slots (see Reference::linear).
    const double mu =
      reference == Reference::linear ? 0. : friction_coefficient();
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
          any = any || (status.slot_state[s] != ContactState::free);
        if (!any)
          continue;
        ++n_active;
        if (node_flags != nullptr)
          (*node_flags)[node] = 1;
        fields.gather(
          layout, field_is_rigid, masses, normals, velocities, node);
        if (impulses != nullptr)
          before = fields.velocities;
        ContactNode<dim> view = fields.view();
        if (reference != Reference::zero && reference != Reference::linear)
          view.allowed = status.allowed.data() + begin;
        ContactLaw<dim>::project_node_frozen(
          view,
          status.slot_state.data() + begin,
          status.slip_directions.data() + begin,
          mu,
          reference == Reference::frozen ? &status.references[begin] :
          reference == Reference::zero   ? &zero :
                                           nullptr);
        fields.scatter(velocities);
        if (impulses != nullptr)
          record_impulses(layout,
                          node,
                          fields.n,
                          fields.masses.data(),
                          fields.rigid.get(),
                          fields.normals.data(),
                          before.data(),
                          fields.velocities.data(),
                          *impulses);
      }

    for (unsigned int w = 0; w < status.wall_slots.size(); ++w)
      if (status.wall_state[w] != ContactState::free)
        {
          const unsigned int   s        = status.wall_slots[w];
          Tensor<1, dim>       velocity = get_slot_vector<dim>(velocities, s);
          const Tensor<1, dim> before   = velocity;
          ContactLaw<dim>::apply_state(
            status.wall_state[w],
            ContactLaw<dim>::face_normal(status.wall_faces[w]),
            reference == Reference::linear ?
              0. :
              ContactLaw<dim>::wall_friction(
                grid.boundary_condition(status.wall_faces[w])),
            status.wall_slip_directions[w],
            Tensor<1, dim>(),
            velocity,
            reference == Reference::zero || reference == Reference::linear ?
              0. :
              status.wall_allowed[w]);
          set_slot_vector<dim>(velocity, velocities, s);
          if (impulses != nullptr)
            impulses->walls[status.wall_faces[w]] +=
              impulses->scale * masses.local_element(s) * (velocity - before);
        }
    return n_active;
  }



  template <int dim>
  void
  GrainContact<dim>::record_impulses(const GrainFieldLayout<dim> &layout,
                                     const unsigned int           node,
                                     const unsigned int           n,
                                     const double                *masses,
                                     const bool                  *rigid,
                                     const Tensor<1, dim>        *normals,
                                     const Tensor<1, dim>        *before,
                                     const Tensor<1, dim>        *after,
                                     ConstraintImpulses<dim> &impulses) const
  {
    const unsigned int begin    = layout.node_slots_begin(node);
    const Point<dim>  &position = grid.node_position(node);
    // One entry: impulse on field `to` from field `from`, normal out of
    // `from`; stored with the grains in increasing order.
    const auto add = [&](const unsigned int    from,
                         const unsigned int    to,
                         const Tensor<1, dim> &impulse,
                         const Tensor<1, dim> &normal) {
      if (impulse.norm_square() == 0.)
        return;
      const unsigned int grain_from = layout.field(begin + from);
      const unsigned int grain_to   = layout.field(begin + to);
      typename ConstraintImpulses<dim>::Pair pair;
      const bool                             in_order = grain_from < grain_to;
      pair.grain_a  = in_order ? grain_from : grain_to;
      pair.grain_b  = in_order ? grain_to : grain_from;
      pair.impulse  = in_order ? impulse : -impulse;
      pair.normal   = in_order ? normal : -normal;
      pair.position = position;
      impulses.pairs.push_back(pair);
    };

    int rigid_field = -1;
    for (unsigned int k = 0; k < n; ++k)
      if (rigid[k] && rigid_field < 0)
        rigid_field = k;
    // The mass of the fields other than k, summed (not the total less
    // m_k, which cancels to zero beside a field of round-off mass).
    const auto others = [&](const unsigned int k) {
      double mass = 0.;
      for (unsigned int q = 0; q < n; ++q)
        if (q != k)
          mass += masses[q];
      return mass;
    };
    const auto impulse = [&](const unsigned int k) {
      return impulses.scale * masses[k] * (after[k] - before[k]);
    };

    if (rigid_field >= 0)
      {
        // Every deformable field was held against the rigid one.
        for (unsigned int k = 0; k < n; ++k)
          if (!rigid[k])
            add(k, rigid_field, -impulse(k), normals[k]);
        return;
      }
    // Deformable fields only: field k's impulse comes from the others in
    // proportion to their masses (exactly from the partner when two meet);
    // the pair's impulse is the mean of the two views, so it is equal and
    // opposite.
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int j = k + 1; j < n; ++j)
        {
          if (masses[k] <= 0. || masses[j] <= 0.)
            continue;
          const Tensor<1, dim> on_j   = masses[k] / others(j) * impulse(j);
          const Tensor<1, dim> on_k   = masses[j] / others(k) * impulse(k);
          Tensor<1, dim>       normal = normals[k] - normals[j];
          const double         length = normal.norm();
          if (length > 0.)
            normal /= length;
          add(k, j, 0.5 * (on_j - on_k), normal);
        }
  }



  template <int dim>
  std::pair<double, double>
  GrainContact<dim>::constraint_work(const GrainFieldLayout<dim> &layout,
                                     const VectorType            &masses,
                                     const VectorType            &before,
                                     const VectorType            &after,
                                     const VectorType            &rate) const
  {
    // Total work of the reactions on the deformable slots, and the part
    // that rigid partners put in: sum over a node's deformable slots of
    // the reactions, times the rigid slot's velocity.
    double total = 0., boundary = 0.;
    for (unsigned int node = 0; node < layout.n_nodes(); ++node)
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int end   = layout.node_slots_end(node);
        Tensor<1, dim>     reaction;
        int                rigid_slot = -1;
        for (unsigned int s = begin; s < end; ++s)
          {
            if (field_is_rigid[layout.field(s)])
              {
                rigid_slot = static_cast<int>(s);
                continue;
              }
            const Tensor<1, dim> impulse =
              masses.local_element(s) * (get_slot_vector<dim>(after, s) -
                                         get_slot_vector<dim>(before, s));
            total += impulse * get_slot_vector<dim>(rate, s);
            reaction += impulse;
          }
        if (rigid_slot >= 0)
          boundary += reaction * get_slot_vector<dim>(rate, rigid_slot);
      }
    return {boundary - total, boundary};
  }



  template class GrainContact<2>;
  template class GrainContact<3>;
} // namespace grainmpm
