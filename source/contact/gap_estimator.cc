// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/gap_estimator.h>

#include <cmath>
#include <limits>

namespace grainmpm
{
  template <int dim>
  GapEstimator<dim>::GapEstimator(const BackgroundGrid<dim>   &grid,
                                  const RigidGrainMotion<dim> &rigid_motion,
                                  const std::vector<bool>     &field_is_rigid,
                                  const bool                   enabled)
    : grid(grid)
    , rigid_motion(rigid_motion)
    , field_is_rigid(field_is_rigid)
    , is_enabled(enabled)
  {}



  template <int dim>
  void
  GapEstimator<dim>::compute(const GrainFieldLayout<dim> &layout,
                             const VectorType            &volumes,
                             const double                 dt)
  {
    // The support of a node, int S_i dx = prod_d h_d, halved for every box
    // face the node lies on.
    double support = 1.;
    for (unsigned int d = 0; d < dim; ++d)
      support *= grid.cell_size()[d];
    this->dt = dt;
    slot_fills.resize(layout.n_slots());
    slot_centroids.resize(layout.n_slots());
    slot_distances.assign(layout.n_slots(),
                          std::numeric_limits<double>::quiet_NaN());
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      {
        const unsigned int node  = layout.node(s);
        const unsigned int faces = grid.node_faces(node);
        // Only contact nodes and the nodes on a box face are read, and only
        // there are the volumes summed (GrainFieldLayout::reads_fill()).
        if (!layout.reads_fill(s))
          {
            slot_fills[s]     = std::numeric_limits<double>::quiet_NaN();
            slot_centroids[s] = Tensor<1, dim>();
            continue;
          }
        if (field_is_rigid[layout.field(s)])
          slot_distances[s] =
            rigid_motion.surface_distance(layout.field(s),
                                          grid.node_position(node));
        const double volume = volumes.local_element((1 + dim) * s);
        slot_fills[s] = volume * (1U << __builtin_popcount(faces)) / support;
        // Centroids only where the walls need them.
        slot_centroids[s] = Tensor<1, dim>();
        if (faces != 0 && volume > 0.)
          {
            const Point<dim> &position = grid.node_position(node);
            for (unsigned int d = 0; d < dim; ++d)
              slot_centroids[s][d] =
                volumes.local_element((1 + dim) * s + 1 + d) / volume -
                position[d];
          }
      }
  }



  template <int dim>
  void
  GapEstimator<dim>::node_allowed_approach(const unsigned int      begin,
                                           const ContactNode<dim> &node,
                                           double *allowed) const
  {
    const Tensor<1, dim> &h               = grid.cell_size();
    double                deformable_mass = 0., fill_sum = 0.;
    bool                  rigid_partner = false;
    // The distance of the node from the surface of the first rigid field
    // (the contact law's partner), where its shape is located.
    double rigid_distance = std::numeric_limits<double>::quiet_NaN();
    for (unsigned int k = 0; k < node.n; ++k)
      {
        fill_sum += slot_fills[begin + k];
        if (node.rigid[k] && !rigid_partner)
          rigid_distance = slot_distances[begin + k];
        if (node.rigid[k])
          rigid_partner = true;
        else
          deformable_mass += node.masses[k];
      }
    for (unsigned int k = 0; k < node.n; ++k)
      {
        allowed[k]                   = 0.;
        const Tensor<1, dim> &normal = node.normals[k];
        if (node.rigid[k] || normal.norm_square() == 0. ||
            !(deformable_mass > 0.))
          continue;
        double h_normal = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          h_normal += (h[d] * normal[d]) * (h[d] * normal[d]);
        // Where the surfaces of this field and of the others lie.
        const double fill = slot_fills[begin + k];
        const double gap =
          std::isfinite(rigid_distance) ?
            rigid_distance -
              std::sqrt(h_normal) * HatKernel::inverse_integral(fill) :
            std::sqrt(h_normal) *
              (HatKernel::inverse_integral(1. - (fill_sum - fill)) -
               HatKernel::inverse_integral(fill));
        if (gap > 0.)
          allowed[k] = (rigid_partner ? 1. :
                                        (deformable_mass - node.masses[k]) /
                                          deformable_mass) *
                       gap / dt;
      }
  }



  template <int dim>
  double
  GapEstimator<dim>::wall_allowed_approach(const unsigned int slot,
                                           const unsigned int face) const
  {
    if (!is_enabled)
      return 0.;
    const double h = grid.cell_size()[face / 2];
    if (!(slot_fills[slot] > 0.))
      return h / dt;
    // The centroid's distance from the face, into the box.
    const double depth =
      (face % 2 == 0 ? 1. : -1.) * slot_centroids[slot][face / 2];
    return h *
           std::min(HatKernel::half_surface_from_centroid(depth / h),
                    HatKernel::inverse_half_integral(slot_fills[slot])) /
           dt;
  }



  template class GapEstimator<2>;
  template class GapEstimator<3>;
} // namespace grainmpm
