// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/contact_law.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  namespace
  {
    // Passes of projection and momentum restoration at nodes where three or
    // more deformable grains meet.
    constexpr unsigned int max_projection_passes = 1000;



    /**
     * What the law needs of a node's fields before it decides: the partner
     * velocity v_ref (the first rigid field's, of infinite mass, or the
     * centre of mass of the deformable fields, Cummins & Brackbill eq. 6)
     * and the deformable fields' momentum, mass and number.
     */
    template <int dim>
    struct NodeReference
    {
      /** False if the node has neither a rigid field nor deformable mass. */
      bool           exists = false;
      Tensor<1, dim> velocity;
      Tensor<1, dim> momentum;
      double         total_mass   = 0.;
      int            rigid_field  = -1;
      unsigned int   n_deformable = 0;
    };



    /** The NodeReference of @p node. */
    template <int dim>
    NodeReference<dim>
    node_reference(const ContactNode<dim> &node, const double floor)
    {
      NodeReference<dim> result;
      for (unsigned int k = 0; k < node.n; ++k)
        if (node.rigid[k])
          {
            if (result.rigid_field < 0)
              result.rigid_field = k;
          }
        else if (node.masses[k] >= floor)
          {
            result.total_mass += node.masses[k];
            result.momentum += node.masses[k] * node.velocities[k];
            ++result.n_deformable;
          }
      result.exists = true;
      // Without a rigid field, a partner needs two fields that are not
      // light (with no light fields, a single field is its own partner
      // and is left alone by the law).
      if (floor > 0. && result.rigid_field < 0 && result.n_deformable < 2)
        result.exists = false;
      if (result.rigid_field >= 0)
        result.velocity = node.velocities[result.rigid_field];
      else if (result.total_mass > 0.)
        result.velocity = result.momentum / result.total_mass;
      else
        result.exists = false;
      return result;
    }



    /**
     * The mass below which a deformable field of @p node is light: its
     * light-field fraction times the largest mass of a deformable field
     * (zero: no field is light).
     */
    template <int dim>
    double
    light_floor(const ContactNode<dim> &node)
    {
      if (!(node.light_fraction > 0.))
        return 0.;
      double heaviest = 0.;
      for (unsigned int k = 0; k < node.n; ++k)
        if (!node.rigid[k])
          heaviest = std::max(heaviest, node.masses[k]);
      return node.light_fraction * heaviest;
    }



    /**
     * Shift all fields with mass, light fields (mass below @p floor)
     * excepted, by the change of their momentum from @p momentum_before
     * over their mass @p total_mass (no rigid field at the node); returns
     * the size of the shift.
     */
    template <int dim>
    double
    restore_momentum(const unsigned int    n_fields,
                     const double         *masses,
                     const double          floor,
                     const Tensor<1, dim> &momentum_before,
                     const double          total_mass,
                     Tensor<1, dim>       *velocities)
    {
      Tensor<1, dim> momentum_after;
      for (unsigned int k = 0; k < n_fields; ++k)
        if (masses[k] >= floor)
          momentum_after += masses[k] * velocities[k];
      const Tensor<1, dim> shift =
        (momentum_after - momentum_before) / total_mass;
      for (unsigned int k = 0; k < n_fields; ++k)
        if (masses[k] > 0. && masses[k] >= floor)
          velocities[k] -= shift;
      return shift.norm();
    }
  } // namespace



  template <int dim>
  ContactState
  ContactLaw<dim>::classify(const Tensor<1, dim> &relative,
                            const Tensor<1, dim> &normal,
                            const double          mu,
                            Tensor<1, dim>       &slip_direction,
                            const double          allowed,
                            const ContactState    previous,
                            const double          band,
                            const bool            keep)
  {
    // D of eq. (5): approaching iff relative . n > 0 (beyond the approach
    // the gap allows); then stick if mu D >= |v_t| (mu' = min(mu, C/D) =
    // C/D removes all relative tangential velocity), else slip by mu D.
    // The hysteresis band shifts both tests against a change of state.
    slip_direction            = Tensor<1, dim>();
    const double normal_speed = relative * normal;
    const double approach     = normal_speed - allowed;
    const double catch_shift =
      band > 0. ? (previous == ContactState::free ? band : -band) : 0.;
    if (!(approach > catch_shift))
      return ContactState::free;
    const Tensor<1, dim> tangential  = relative - normal_speed * normal;
    const double         slip        = tangential.norm();
    const double         stick_shift = band > 0. ?
                                         (previous == ContactState::sticking ? band :
                                          previous == ContactState::sliding ? -band :
                                                                              0.) :
                                         0.;
    // The friction bound is mu times the approach the constraint removes:
    // the whole normal speed, or what exceeds the kept approach.
    const double removed = keep ? approach : normal_speed;
    if (mu > 0. && mu * removed + stick_shift >= slip)
      return ContactState::sticking;
    if (mu > 0.)
      slip_direction = tangential / slip;
    return ContactState::sliding;
  }



  template <int dim>
  void
  ContactLaw<dim>::apply_state(const ContactState    state,
                               const Tensor<1, dim> &normal,
                               const double          mu,
                               const Tensor<1, dim> &slip_direction,
                               const Tensor<1, dim> &reference,
                               Tensor<1, dim>       &velocity,
                               const double          kept)
  {
    if (state == ContactState::sticking)
      velocity = reference + kept * normal;
    else if (state == ContactState::sliding)
      {
        const double approach = (velocity - reference) * normal - kept;
        velocity -= approach * normal + (mu * approach) * slip_direction;
      }
  }



  template <int dim>
  bool
  ContactLaw<dim>::decide_and_project(const ContactLawOptions &options,
                                      const ContactNode<dim>  &node,
                                      const double             floor,
                                      const Tensor<1, dim>    &reference,
                                      ContactState            *states,
                                      Tensor<1, dim>          *slip_directions,
                                      const ContactState      *previous_states)
  {
    const double          mu         = options.friction();
    const double         *masses     = node.masses;
    const bool           *rigid      = node.rigid;
    const Tensor<1, dim> *normals    = node.normals;
    Tensor<1, dim>       *velocities = node.velocities;
    const double         *allowed    = node.allowed;
    bool                  corrected  = false;
    for (unsigned int k = 0; k < node.n; ++k)
      {
        if (rigid[k] || !(masses[k] > options.mass_threshold) ||
            masses[k] < floor)
          continue;
        ContactState   state = ContactState::sticking;
        Tensor<1, dim> slip_direction;
        double         kept = 0.;
        // Without contact (a single deformable field), deformable
        // material sticks to a rigid body.
        if (options.model != ContactModel::none)
          {
            if (normals[k].norm_square() == 0.)
              continue;
            const double allowed_k = allowed != nullptr ? allowed[k] : 0.;
            state                  = classify(velocities[k] - reference,
                             normals[k],
                             mu,
                             slip_direction,
                             allowed_k,
                             previous_states != nullptr ? previous_states[k] :
                                                                           ContactState::free,
                             previous_states != nullptr ? options.band : 0.,
                             options.keep_allowed_approach);
            if (state == ContactState::free)
              continue; // separating: free
            if (options.keep_allowed_approach)
              kept = allowed_k;
          }
        apply_state(state,
                    normals[k],
                    mu,
                    slip_direction,
                    reference,
                    velocities[k],
                    kept);
        if (states != nullptr)
          {
            states[k]          = state;
            slip_directions[k] = slip_direction;
          }
        corrected = true;
      }
    return corrected;
  }



  template <int dim>
  bool
  ContactLaw<dim>::project_node(const ContactLawOptions &options,
                                const ContactNode<dim>  &node)
  {
    if (node.states != nullptr)
      for (unsigned int k = 0; k < node.n; ++k)
        {
          node.states[k]          = ContactState::free;
          node.slip_directions[k] = Tensor<1, dim>();
        }
    const double             floor     = light_floor(node);
    const NodeReference<dim> partner   = node_reference(node, floor);
    const Tensor<1, dim>    &reference = partner.velocity;
    if (node.reference != nullptr)
      *node.reference = reference;
    if (!partner.exists)
      return false;

    const bool corrected = decide_and_project(options,
                                              node,
                                              floor,
                                              reference,
                                              node.states,
                                              node.slip_directions,
                                              node.previous_states);
    // Two deformable fields (antiparallel normals) or a rigid partner: one
    // pass conserves momentum, respectively is all there is. Three or more
    // deformable fields: the normals cannot all be pairwise antiparallel and
    // the pass changes the node's momentum. Remove that change by a common
    // velocity shift and decide and project again, until no field
    // approaches and the momentum is restored (the state "all fields at
    // v_cm" satisfies both, so the alternation has a fixed point; it
    // converges in a few passes). End on exact momentum. Only the first
    // pass's decisions are recorded (and have the hysteresis).
    if (corrected && partner.rigid_field < 0 && partner.n_deformable > 2)
      {
        double velocity_scale = 0.;
        for (unsigned int k = 0; k < node.n; ++k)
          velocity_scale =
            std::max(velocity_scale, (node.velocities[k] - reference).norm());
        for (unsigned int pass = 0; pass < max_projection_passes; ++pass)
          if (restore_momentum(node.n,
                               node.masses,
                               floor,
                               partner.momentum,
                               partner.total_mass,
                               node.velocities) <= 1e-14 * velocity_scale ||
              !decide_and_project(
                options, node, floor, reference, nullptr, nullptr, nullptr))
            break;
        restore_momentum(node.n,
                         node.masses,
                         floor,
                         partner.momentum,
                         partner.total_mass,
                         node.velocities);
      }
    return corrected;
  }



  template <int dim>
  void
  ContactLaw<dim>::project_node_frozen(const ContactNode<dim> &node,
                                       const ContactState     *states,
                                       const Tensor<1, dim>   *slip_directions,
                                       const double            mu,
                                       const Tensor<1, dim>   *fixed_reference)
  {
    const double             floor     = light_floor(node);
    const NodeReference<dim> partner   = node_reference(node, floor);
    Tensor<1, dim>           reference = partner.velocity;
    if (fixed_reference != nullptr)
      reference = *fixed_reference;

    for (unsigned int k = 0; k < node.n; ++k)
      if (node.rigid[k] || node.masses[k] >= floor)
        apply_state(states[k],
                    node.normals[k],
                    mu,
                    slip_directions[k],
                    reference,
                    node.velocities[k],
                    node.allowed != nullptr ? node.allowed[k] : 0.);
    // Three or more deformable fields: one momentum-restoring shift. The
    // map stays linear in the velocities; alternating it with the frozen
    // projection until the shift vanishes converges slowly without
    // friction and diverges with it (tests/contact/frozen_multi_grain_01).
    if (fixed_reference == nullptr && partner.rigid_field < 0 &&
        partner.n_deformable > 2)
      restore_momentum(node.n,
                       node.masses,
                       floor,
                       partner.momentum,
                       partner.total_mass,
                       node.velocities);
  }



  template <int dim>
  ContactState
  ContactLaw<dim>::classify_wall(const BoundaryCondition &condition,
                                 const Tensor<1, dim>    &normal,
                                 const Tensor<1, dim>    &velocity,
                                 Tensor<1, dim>          &slip_direction,
                                 const double             allowed,
                                 const ContactState       previous,
                                 const double             band,
                                 const bool               keep)
  {
    slip_direction = Tensor<1, dim>();
    switch (condition.type)
      {
        case BoundaryType::open:
          return ContactState::free;
        case BoundaryType::no_slip:
          return ContactState::sticking;
        case BoundaryType::free_slip:
        case BoundaryType::friction:
          // Unilateral: only motion into the wall is removed, so grains
          // can rebound and leave.
          return classify(velocity,
                          normal,
                          wall_friction(condition),
                          slip_direction,
                          allowed,
                          previous,
                          band,
                          keep);
      }
    return ContactState::free;
  }



  template <int dim>
  void
  ContactLaw<dim>::apply_wall(const BoundaryCondition &condition,
                              const Tensor<1, dim>    &normal,
                              Tensor<1, dim>          &velocity,
                              const double             allowed,
                              const double             turning)
  {
    const Tensor<1, dim> shift    = wall_turning(condition, turning) * normal;
    Tensor<1, dim>       relative = velocity - shift;
    Tensor<1, dim>       slip_direction;
    const ContactState   state =
      classify_wall(condition, normal, relative, slip_direction, allowed);
    apply_state(state,
                normal,
                wall_friction(condition),
                slip_direction,
                Tensor<1, dim>(),
                relative);
    velocity = relative + shift;
  }



  template class ContactLaw<2>;
  template class ContactLaw<3>;
} // namespace grainmpm
