// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/constraint_impulses.h>

namespace grainmpm
{
  template <int dim>
  void
  ConstraintImpulses<dim>::add_node(const GrainFieldLayout<dim> &layout,
                                    const unsigned int           node,
                                    const Point<dim>            &position,
                                    const ContactNode<dim>      &fields,
                                    const Tensor<1, dim>        *before)
  {
    const unsigned int    n       = fields.n;
    const double         *masses  = fields.masses;
    const bool           *rigid   = fields.rigid;
    const Tensor<1, dim> *normals = fields.normals;
    const Tensor<1, dim> *after   = fields.velocities;
    const unsigned int    begin   = layout.node_slots_begin(node);
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
      Pair               pair;
      const bool         in_order = grain_from < grain_to;
      pair.grain_a                = in_order ? grain_from : grain_to;
      pair.grain_b                = in_order ? grain_to : grain_from;
      pair.impulse                = in_order ? impulse : -impulse;
      pair.normal                 = in_order ? normal : -normal;
      pair.position               = position;
      pairs.push_back(pair);
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
      return scale * masses[k] * (after[k] - before[k]);
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
  constraint_work(const GrainFieldLayout<dim> &layout,
                  const std::vector<bool>     &field_is_rigid,
                  const LinearAlgebra::distributed::Vector<double> &masses,
                  const LinearAlgebra::distributed::Vector<double> &before,
                  const LinearAlgebra::distributed::Vector<double> &after,
                  const LinearAlgebra::distributed::Vector<double> &rate)
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



  template <int dim>
  double
  normal_constraint_dissipation(
    const GrainFieldLayout<dim>                      &layout,
    const std::vector<bool>                          &field_is_rigid,
    const LinearAlgebra::distributed::Vector<double> &masses,
    const LinearAlgebra::distributed::Vector<double> &normals,
    const LinearAlgebra::distributed::Vector<double> &before,
    const LinearAlgebra::distributed::Vector<double> &after,
    const LinearAlgebra::distributed::Vector<double> &rate)
  {
    double dissipation = 0.;
    for (unsigned int node = 0; node < layout.n_nodes(); ++node)
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int end   = layout.node_slots_end(node);
        Tensor<1, dim>     reference, momentum;
        double             mass       = 0.;
        bool               has_rigid  = false;
        bool               has_change = false;
        for (unsigned int s = begin; s < end; ++s)
          if (field_is_rigid[layout.field(s)])
            {
              reference = get_slot_vector<dim>(rate, s);
              has_rigid = true;
            }
          else
            {
              momentum +=
                masses.local_element(s) * get_slot_vector<dim>(rate, s);
              mass += masses.local_element(s);
              has_change = has_change || get_slot_vector<dim>(after, s) !=
                                           get_slot_vector<dim>(before, s);
            }
        if (!has_change)
          continue;
        if (!has_rigid && end - begin > 1 && mass > 0.)
          reference = momentum / mass;
        for (unsigned int s = begin; s < end; ++s)
          {
            if (field_is_rigid[layout.field(s)])
              continue;
            // A slot without a contact normal (a wall's node): along its
            // impulse.
            const Tensor<1, dim> change =
              get_slot_vector<dim>(after, s) - get_slot_vector<dim>(before, s);
            Tensor<1, dim> normal = get_slot_vector<dim>(normals, s);
            if (!(normal.norm() > 0.))
              normal = change;
            const double length = normal.norm();
            if (!(length > 0.))
              continue;
            normal /= length;
            const double impulse = masses.local_element(s) * (change * normal);
            dissipation -=
              impulse * ((get_slot_vector<dim>(rate, s) - reference) * normal);
          }
      }
    return dissipation;
  }



  template struct ConstraintImpulses<2>;
  template struct ConstraintImpulses<3>;
  template std::pair<double, double>
  constraint_work<2>(const GrainFieldLayout<2> &,
                     const std::vector<bool> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &);
  template std::pair<double, double>
  constraint_work<3>(const GrainFieldLayout<3> &,
                     const std::vector<bool> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &,
                     const LinearAlgebra::distributed::Vector<double> &);
  template double
  normal_constraint_dissipation<2>(
    const GrainFieldLayout<2> &,
    const std::vector<bool> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &);
  template double
  normal_constraint_dissipation<3>(
    const GrainFieldLayout<3> &,
    const std::vector<bool> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &);
} // namespace grainmpm
