// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/grain_contact.h>

#include <cmath>

namespace grainmpm
{
  template <int dim>
  GrainContact<dim>::GrainContact(const ContactParameters   &parameters,
                                  const BackgroundGrid<dim> &grid,
                                  const std::vector<bool>   &field_is_rigid)
    : parameters(parameters)
    , grid(grid)
    , field_is_rigid(field_is_rigid)
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



  namespace
  {
    // Passes of projection and momentum restoration at nodes where three or
    // more deformable grains meet.
    constexpr unsigned int max_projection_passes = 1000;
  } // namespace



  template <int dim>
  bool
  GrainContact<dim>::project_node(const unsigned int    n_fields,
                                  const double         *masses,
                                  const bool           *rigid,
                                  const Tensor<1, dim> *normals,
                                  Tensor<1, dim>       *velocities,
                                  const ContactModel    model,
                                  const double          friction_coefficient)
  {
    // The reference velocity: a rigid field has infinite mass, otherwise
    // the centre of mass of the node (eq. 6).
    Tensor<1, dim> reference_velocity, momentum_before;
    double         total_mass   = 0.;
    int            rigid_field  = -1;
    unsigned int   n_deformable = 0;
    for (unsigned int k = 0; k < n_fields; ++k)
      if (rigid[k])
        {
          if (rigid_field < 0)
            rigid_field = k;
        }
      else
        {
          total_mass += masses[k];
          momentum_before += masses[k] * velocities[k];
          ++n_deformable;
        }
    if (rigid_field >= 0)
      reference_velocity = velocities[rigid_field];
    else if (total_mass > 0.)
      reference_velocity = momentum_before / total_mass;
    else
      return false;

    // One pass of eq. (5) over the fields; returns whether one was corrected.
    const auto project_once = [&]() {
      bool corrected_in_pass = false;
      for (unsigned int k = 0; k < n_fields; ++k)
        {
          if (rigid[k] || !(masses[k] > 0.))
            continue;
          if (model == ContactModel::none)
            {
              // Single field: deformable material sticks to a rigid body.
              velocities[k]     = reference_velocity;
              corrected_in_pass = true;
              continue;
            }
          const Tensor<1, dim> &normal = normals[k];
          if (normal.norm_square() == 0.)
            continue;
          const Tensor<1, dim> relative = velocities[k] - reference_velocity;
          const double         approach = relative * normal; // D of eq. (5)
          if (!(approach > 0.))
            continue; // separating: free
          Tensor<1, dim> correction = approach * normal;
          if (model == ContactModel::coulomb_friction)
            {
              const Tensor<1, dim> tangential = relative - approach * normal;
              const double         slip       = tangential.norm(); // C
              if (slip > 0.)
                {
                  // mu' = min(mu, C/D): stick removes all relative
                  // tangential velocity, slip reduces it by mu D.
                  const double effective =
                    std::min(friction_coefficient, slip / approach);
                  correction += (effective * approach / slip) * tangential;
                }
            }
          velocities[k] -= correction;
          corrected_in_pass = true;
        }
      return corrected_in_pass;
    };

    bool corrected = project_once();

    // Two deformable fields (antiparallel normals) or a rigid partner: one
    // pass conserves momentum, respectively is all there is. Three or more
    // deformable fields: the normals cannot all be pairwise antiparallel and
    // the pass changes the node's momentum. Remove that change by a common
    // velocity shift and project again, until no field approaches and the
    // momentum is restored (the state "all fields at v_cm" satisfies both,
    // so the alternation has a fixed point; it converges in a few passes).
    if (corrected && rigid_field < 0 && n_deformable > 2)
      {
        double velocity_scale = 0.;
        for (unsigned int k = 0; k < n_fields; ++k)
          velocity_scale =
            std::max(velocity_scale,
                     (velocities[k] - reference_velocity).norm());
        // Shift all fields by the momentum change over the node mass;
        // return the size of the shift.
        const auto restore_momentum = [&]() {
          Tensor<1, dim> momentum_after;
          for (unsigned int k = 0; k < n_fields; ++k)
            momentum_after += masses[k] * velocities[k];
          const Tensor<1, dim> shift =
            (momentum_after - momentum_before) / total_mass;
          for (unsigned int k = 0; k < n_fields; ++k)
            if (masses[k] > 0.)
              velocities[k] -= shift;
          return shift.norm();
        };
        for (unsigned int pass = 0; pass < max_projection_passes; ++pass)
          if (restore_momentum() <= 1e-14 * velocity_scale || !project_once())
            break;
        // End on exact momentum: a last shift of round-off size.
        restore_momentum();
      }
    return corrected;
  }



  template <int dim>
  unsigned int
  GrainContact<dim>::apply_contact(
    const GrainFieldLayout<dim> &layout,
    const VectorType            &masses,
    const VectorType            &normals,
    VectorType                  &velocities,
    std::vector<unsigned char>  &node_in_contact) const
  {
    std::vector<double>         node_masses;
    std::vector<Tensor<1, dim>> node_normals, node_velocities;
    // Flags for the largest node, allocated once (std::vector<bool> has no
    // data()).
    unsigned int max_fields = 0;
    for (const unsigned int node : layout.contact_nodes())
      max_fields =
        std::max(max_fields,
                 layout.node_slots_end(node) - layout.node_slots_begin(node));
    const std::unique_ptr<bool[]> rigid_flags(new bool[max_fields]);
    unsigned int                  n_corrected = 0;
    for (const unsigned int node : layout.contact_nodes())
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int n     = layout.node_slots_end(node) - begin;
        node_masses.resize(n);
        node_normals.resize(n);
        node_velocities.resize(n);
        for (unsigned int k = 0; k < n; ++k)
          {
            node_masses[k]     = masses.local_element(begin + k);
            rigid_flags[k]     = field_is_rigid[layout.field(begin + k)];
            node_normals[k]    = get_slot_vector<dim>(normals, begin + k);
            node_velocities[k] = get_slot_vector<dim>(velocities, begin + k);
          }
        if (project_node(n,
                         node_masses.data(),
                         rigid_flags.get(),
                         node_normals.data(),
                         node_velocities.data(),
                         parameters.model,
                         parameters.friction_coefficient))
          {
            for (unsigned int k = 0; k < n; ++k)
              set_slot_vector<dim>(node_velocities[k], velocities, begin + k);
            node_in_contact[node] = 1;
            ++n_corrected;
          }
      }
    return n_corrected;
  }



  template <int dim>
  void
  GrainContact<dim>::apply_wall(const BoundaryCondition &condition,
                                const Tensor<1, dim>    &normal,
                                Tensor<1, dim>          &velocity)
  {
    switch (condition.type)
      {
        case BoundaryType::open:
          return;
        case BoundaryType::no_slip:
          velocity = 0.;
          return;
        case BoundaryType::free_slip:
        case BoundaryType::friction:
          {
            // Unilateral: only motion into the wall is removed, so grains
            // can rebound and leave (reference/physics.md section 2.5).
            const double approach = velocity * normal;
            if (!(approach > 0.))
              return;
            Tensor<1, dim> tangential = velocity - approach * normal;
            velocity                  = tangential;
            const double slip         = tangential.norm();
            if (condition.type == BoundaryType::friction && slip > 0.)
              velocity -=
                (std::min(condition.friction_coefficient, slip / approach) *
                 approach / slip) *
                tangential;
            return;
          }
      }
  }



  template <int dim>
  void
  GrainContact<dim>::apply_walls(const GrainFieldLayout<dim> &layout,
                                 VectorType                  &velocities) const
  {
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
                  apply_wall(grid.boundary_condition(face),
                             face_normal(face),
                             velocity);
                }
            set_slot_vector<dim>(velocity, velocities, s);
          }
      }
  }



  template class GrainContact<2>;
  template class GrainContact<3>;
} // namespace grainmpm
