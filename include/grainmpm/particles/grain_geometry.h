// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_grain_geometry_h
#define grainmpm_particles_grain_geometry_h

#include <grainmpm/particles/grain_parameters.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <utility>

namespace grainmpm
{
  /**
   * True if @p point lies strictly inside the shape of @p grain (a checked
   * grain: GrainParameters::check() has set its shape and vertices).
   * Rectangles and boxes are rotated by Rotation degrees about their centre
   * (about the z axis in 3D); polygons use the even-odd rule.
   */
  template <int dim>
  bool
  contains(const GrainParameters<dim> &grain, const dealii::Point<dim> &point);

  /**
   * The lower and upper corners of an axis-aligned box that contains the
   * shape of @p grain (a checked grain).
   */
  template <int dim>
  std::pair<dealii::Point<dim>, dealii::Point<dim>>
  bounding_box(const GrainParameters<dim> &grain);

  /**
   * The outward unit normal of the shape of @p grain (a checked grain) seen
   * from @p point: the gradient of the signed distance to its boundary,
   * that is the direction from the nearest boundary point to @p point
   * outside the shape, and the outward normal of the nearest face (edge)
   * inside it. Zero where that direction is not defined (the centre of a
   * disk or sphere).
   */
  template <int dim>
  dealii::Tensor<1, dim>
  outward_normal(const GrainParameters<dim> &grain,
                 const dealii::Point<dim>   &point);

  /**
   * The signed distance from @p point to the boundary of the shape of
   * @p grain (a checked grain), negative inside; @p normal is set to
   * outward_normal().
   */
  template <int dim>
  double
  signed_distance(const GrainParameters<dim> &grain,
                  const dealii::Point<dim>   &point,
                  dealii::Tensor<1, dim>     &normal);

} // namespace grainmpm

#endif
