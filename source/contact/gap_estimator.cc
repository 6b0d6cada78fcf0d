// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/gap_estimator.h>
#include <grainmpm/particles/grain_geometry.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainmpm
{
  template <int dim>
  GapEstimator<dim>::GapEstimator(
    const BackgroundGrid<dim>               &grid,
    const RigidGrainMotion<dim>             &rigid_motion,
    const std::vector<bool>                 &field_is_rigid,
    const std::vector<bool>                 &field_keeps_shape,
    const std::vector<GrainInfo<dim>>       &grains,
    const std::vector<GrainParameters<dim>> &grain_parameters,
    const bool                               enabled,
    const bool                               use_shapes)
    : grid(grid)
    , rigid_motion(rigid_motion)
    , field_is_rigid(field_is_rigid)
    , field_keeps_shape(field_keeps_shape)
    , grains(grains)
    , grain_parameters(grain_parameters)
    , is_enabled(enabled)
    , use_shapes(use_shapes)
  {}



  template <int dim>
  std::vector<Tensor<1, dim>>
  GapEstimator<dim>::shape_displacements(const GrainFieldLayout<dim> &layout,
                                         const VectorType &masses) const
  {
    const unsigned int n_fields = field_keeps_shape.size();
    // Per field its mass and first moment, 1 + dim numbers.
    std::vector<double> sums(n_fields * (1 + dim), 0.);
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      {
        const unsigned int field = layout.field(s);
        if (!field_keeps_shape[field])
          continue;
        const double      mass     = masses.local_element(s);
        const Point<dim> &position = grid.node_position(layout.node(s));
        sums[field * (1 + dim)] += mass;
        for (unsigned int d = 0; d < dim; ++d)
          sums[field * (1 + dim) + 1 + d] += mass * position[d];
      }
    Utilities::MPI::sum(sums, layout.get_communicator(), sums);
    std::vector<Tensor<1, dim>> displacements(n_fields);
    for (unsigned int field = 0; field < n_fields; ++field)
      if (sums[field * (1 + dim)] > 0.)
        for (unsigned int d = 0; d < dim; ++d)
          displacements[field][d] =
            sums[field * (1 + dim) + 1 + d] / sums[field * (1 + dim)] -
            grains[field].centroid[d];
    return displacements;
  }



  template <int dim>
  std::vector<bool>
  GapEstimator<dim>::move_shapes(std::vector<double> sums,
                                 const MPI_Comm      communicator)
  {
    constexpr unsigned int n_sums   = Transfer<dim>::n_shape_sums;
    const unsigned int     n_fields = field_keeps_shape.size();
    AssertDimension(sums.size(), n_sums * n_fields);
    Utilities::MPI::sum(sums, communicator, sums);
    double h = grid.cell_size()[0];
    for (unsigned int d = 1; d < dim; ++d)
      h = std::min(h, grid.cell_size()[d]);
    std::vector<bool> unstrained(n_fields, false);
    shape_centres.assign(n_fields, Point<dim>());
    shape_angular_velocities.assign(n_fields, Tensor<1, 3>());
    for (unsigned int field = 0; field < n_fields; ++field)
      {
        const double *const q    = sums.data() + n_sums * field;
        const double        mass = q[0];
        if (!field_keeps_shape[field] || !(mass > 0.))
          continue;
        // The mean strain |E| times the radius against a tenth of a cell.
        unstrained[field] =
          q[1] * grain_parameters[field].radius <= 0.1 * h * mass;
        // About the centre of mass c: L_c = L - c x P and the second
        // moment J_c = J - M c (x) c; the inertia tr(J_c) I - J_c.
        const double *const first_moment = q + 2;
        const double *const momentum     = first_moment + dim;
        const double *const angular      = momentum + dim;
        const double *const second       = angular + (dim == 2 ? 1 : 3);
        Point<dim>          c;
        for (unsigned int d = 0; d < dim; ++d)
          c[d] = first_moment[d] / mass;
        shape_centres[field] = c;
        Tensor<2, dim> J;
        for (unsigned int d = 0; d < dim; ++d)
          for (unsigned int e = 0; e < dim; ++e)
            J[d][e] = second[d * dim + e] - mass * c[d] * c[e];
        if constexpr (dim == 2)
          {
            const double L =
              angular[0] - (c[0] * momentum[1] - c[1] * momentum[0]);
            const double inertia = trace(J);
            if (inertia > 0.)
              shape_angular_velocities[field][2] = L / inertia;
          }
        else
          {
            Tensor<1, dim> L, P;
            for (unsigned int d = 0; d < dim; ++d)
              {
                L[d] = angular[d];
                P[d] = momentum[d];
              }
            L -= cross_product_3d(c, P);
            Tensor<2, 3> inertia;
            for (unsigned int d = 0; d < 3; ++d)
              for (unsigned int e = 0; e < 3; ++e)
                inertia[d][e] = (d == e ? trace(J) : 0.) - J[d][e];
            if (determinant(inertia) > 0.)
              shape_angular_velocities[field] = invert(inertia) * L;
          }
      }
    return unstrained;
  }



  template <int dim>
  double
  GapEstimator<dim>::shape_distance(const unsigned int slot,
                                    const double       fill,
                                    const double       h_normal) const
  {
    const double distance = slot_shape_distances[slot];
    if (!std::isfinite(distance))
      return distance;
    // The fill sees no farther than a cell: compare within that reach.
    const double from_fill = -h_normal * HatKernel::inverse_integral(fill);
    const double reach     = std::clamp(distance, -h_normal, h_normal);
    return std::abs(reach - from_fill) <= 0.5 * h_normal ?
             distance :
             std::numeric_limits<double>::quiet_NaN();
  }



  template <int dim>
  void
  GapEstimator<dim>::compute(const GrainFieldLayout<dim> &layout,
                             const std::vector<double>   &shape_sums,
                             const VectorType            &masses,
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
    slot_shape_distances.assign(layout.n_slots(),
                                std::numeric_limits<double>::quiet_NaN());
    const bool any_shape =
      use_shapes &&
      std::find(field_keeps_shape.begin(), field_keeps_shape.end(), true) !=
        field_keeps_shape.end();
    slot_turning_velocities.assign(layout.n_slots(), Tensor<1, dim>());
    const std::vector<bool> unstrained =
      any_shape ? move_shapes(shape_sums, layout.get_communicator()) :
                  std::vector<bool>(field_keeps_shape.size(), false);
    const std::vector<Tensor<1, dim>> displacements =
      any_shape ? shape_displacements(layout, masses) :
                  std::vector<Tensor<1, dim>>();
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
        const unsigned int field = layout.field(s);
        if (field_is_rigid[field])
          slot_distances[s] =
            rigid_motion.surface_distance(field, grid.node_position(node));
        else if (unstrained[field])
          {
            Tensor<1, dim> normal;
            slot_shape_distances[s] =
              signed_distance(grain_parameters[field],
                              grid.node_position(node) - displacements[field],
                              normal);
          }
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
            // The rotation of the shape about its centre at the centroid of
            // the node's material (omega x r).
            if (std::isfinite(slot_shape_distances[s]))
              {
                const Tensor<1, dim> r =
                  position + slot_centroids[s] - shape_centres[field];
                const Tensor<1, 3> &omega = shape_angular_velocities[field];
                if constexpr (dim == 2)
                  slot_turning_velocities[s] =
                    Tensor<1, dim>({-omega[2] * r[1], omega[2] * r[0]});
                else
                  slot_turning_velocities[s] = cross_product_3d(omega, r);
              }
          }
      }
  }



  template <int dim>
  double
  GapEstimator<dim>::normal_cell_size(const Tensor<1, dim> &normal) const
  {
    const Tensor<1, dim> &h      = grid.cell_size();
    double                result = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      result += (h[d] * normal[d]) * (h[d] * normal[d]);
    return std::sqrt(result);
  }



  template <int dim>
  void
  GapEstimator<dim>::node_allowed_approach(const unsigned int      begin,
                                           const ContactNode<dim> &node,
                                           double *allowed) const
  {
    double deformable_mass = 0., fill_sum = 0.;
    bool   rigid_partner = false;
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
        const double h_normal = normal_cell_size(normal);
        // Where the surfaces of this field and of the others lie; against a
        // located rigid grain, this field's from its shape where that is
        // known and agrees with its fill.
        const double fill = slot_fills[begin + k];
        double       gap  = 0.;
        if (std::isfinite(rigid_distance))
          {
            const double own = shape_distance(begin + k, fill, h_normal);
            gap              = rigid_distance +
                  (std::isfinite(own) ?
                     own :
                     -h_normal * HatKernel::inverse_integral(fill));
          }
        else
          gap =
            h_normal * (HatKernel::inverse_integral(1. - (fill_sum - fill)) -
                        HatKernel::inverse_integral(fill));
        const double share =
          rigid_partner ? 1. :
                          (deformable_mass - node.masses[k]) / deformable_mass;
        if (gap > 0.)
          allowed[k] = share * gap / dt;
      }
  }



  template <int dim>
  bool
  GapEstimator<dim>::wall_reads_shape(const unsigned int slot,
                                      const unsigned int face,
                                      double            &gap) const
  {
    const double h = grid.cell_size()[face / 2];
    // The centroid's distance from the face, into the box.
    const double depth =
      (face % 2 == 0 ? 1. : -1.) * slot_centroids[slot][face / 2];
    gap = h * std::min(HatKernel::half_surface_from_centroid(depth / h),
                       HatKernel::inverse_half_integral(slot_fills[slot]));
    // The node lies on the wall: the gap is its distance from the shape,
    // where that agrees with the fill.
    const double shape = slot_shape_distances[slot];
    return std::isfinite(shape) &&
           std::abs(std::clamp(shape, -h, h) - gap) <= 0.5 * h;
  }



  template <int dim>
  double
  GapEstimator<dim>::wall_allowed_approach(const unsigned int slot,
                                           const unsigned int face) const
  {
    if (!is_enabled)
      return 0.;
    if (!(slot_fills[slot] > 0.))
      return grid.cell_size()[face / 2] / dt;
    double gap = 0.;
    if (wall_reads_shape(slot, face, gap))
      return std::max(slot_shape_distances[slot], 0.) / dt;
    return gap / dt;
  }



  template <int dim>
  double
  GapEstimator<dim>::wall_turning_speed(const unsigned int slot,
                                        const unsigned int face) const
  {
    double gap = 0.;
    if (!is_enabled || !(slot_fills[slot] > 0.) ||
        !wall_reads_shape(slot, face, gap))
      return 0.;
    // Along the outward normal of the face.
    return (face % 2 == 0 ? -1. : 1.) * slot_turning_velocities[slot][face / 2];
  }



  template class GapEstimator<2>;
  template class GapEstimator<3>;
} // namespace grainmpm
