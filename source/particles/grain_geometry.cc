// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/grain_geometry.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  template <int dim>
  bool
  contains(const GrainParameters<dim> &grain, const dealii::Point<dim> &point)
  {
    switch (grain.shape)
      {
        case GrainShape::disk:
        case GrainShape::sphere:
          return point.distance_square(grain.centre) <
                 grain.radius * grain.radius;

        case GrainShape::rectangle:
        case GrainShape::box:
          {
            // Rotate the point back into the frame of the unrotated box.
            dealii::Tensor<1, dim> local = point - grain.centre;
            if (grain.rotation != 0.)
              {
                const double angle = -grain.rotation * M_PI / 180.;
                const double x     = local[0];
                const double y     = local[1];
                local[0]           = std::cos(angle) * x - std::sin(angle) * y;
                local[1]           = std::sin(angle) * x + std::cos(angle) * y;
              }
            for (unsigned int d = 0; d < dim; ++d)
              if (!(std::abs(local[d]) < 0.5 * grain.size[d]))
                return false;
            return true;
          }

        case GrainShape::polygon:
          {
            // Even-odd (ray casting) rule.
            const std::vector<dealii::Point<dim>> &vertices = grain.vertices;
            bool                                   inside   = false;
            const unsigned int                     n        = vertices.size();
            for (unsigned int i = 0, j = n - 1; i < n; j = i++)
              {
                const dealii::Point<dim> &a = vertices[i];
                const dealii::Point<dim> &b = vertices[j];
                if ((a[1] > point[1]) != (b[1] > point[1]))
                  {
                    const double x_cross =
                      (b[0] - a[0]) * (point[1] - a[1]) / (b[1] - a[1]) + a[0];
                    if (point[0] < x_cross)
                      inside = !inside;
                  }
              }
            return inside;
          }
      }
    return false;
  }



  template <int dim>
  std::pair<dealii::Point<dim>, dealii::Point<dim>>
  bounding_box(const GrainParameters<dim> &grain)
  {
    const dealii::Point<dim> &centre = grain.centre;
    dealii::Point<dim>        lower, upper;
    switch (grain.shape)
      {
        case GrainShape::disk:
        case GrainShape::sphere:
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = centre[d] - grain.radius;
              upper[d] = centre[d] + grain.radius;
            }
          break;
        case GrainShape::rectangle:
        case GrainShape::box:
          {
            const dealii::Tensor<1, dim> &size  = grain.size;
            const double                  angle = grain.rotation * M_PI / 180.;
            const double                  c     = std::abs(std::cos(angle)),
                         s                      = std::abs(std::sin(angle));
            dealii::Tensor<1, dim> half;
            half[0] = 0.5 * (c * size[0] + s * size[1]);
            half[1] = 0.5 * (s * size[0] + c * size[1]);
            if (dim == 3)
              half[dim - 1] = 0.5 * size[dim - 1];
            lower = centre - half;
            upper = centre + half;
            break;
          }
        case GrainShape::polygon:
          lower = upper = grain.vertices[0];
          for (const auto &vertex : grain.vertices)
            for (unsigned int d = 0; d < dim; ++d)
              {
                lower[d] = std::min(lower[d], vertex[d]);
                upper[d] = std::max(upper[d], vertex[d]);
              }
          break;
      }
    return {lower, upper};
  }



  template bool
  contains<2>(const GrainParameters<2> &, const dealii::Point<2> &);
  template bool
  contains<3>(const GrainParameters<3> &, const dealii::Point<3> &);
  template std::pair<dealii::Point<2>, dealii::Point<2>>
  bounding_box<2>(const GrainParameters<2> &);
  template std::pair<dealii::Point<3>, dealii::Point<3>>
  bounding_box<3>(const GrainParameters<3> &);
} // namespace grainmpm
