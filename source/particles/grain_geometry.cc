// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/grain_geometry.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainmpm
{
  namespace
  {
    /** @p v rotated by @p degrees about the z axis (the x-y plane). */
    template <int dim>
    dealii::Tensor<1, dim>
    rotated(const dealii::Tensor<1, dim> &v, const double degrees)
    {
      if (degrees == 0.)
        return v;
      const double           angle  = degrees * M_PI / 180.;
      dealii::Tensor<1, dim> result = v;
      result[0] = std::cos(angle) * v[0] - std::sin(angle) * v[1];
      result[1] = std::sin(angle) * v[0] + std::cos(angle) * v[1];
      return result;
    }



    /**
     * The signed distance from @p local (in the box's frame) to the
     * boundary of a box of half sizes @p half centred at the origin, and in
     * @p normal the outward normal seen from there.
     */
    template <int dim>
    double
    box_distance(const dealii::Tensor<1, dim> &half,
                 const dealii::Tensor<1, dim> &local,
                 dealii::Tensor<1, dim>       &normal)
    {
      dealii::Tensor<1, dim> outside;
      bool                   inside  = true;
      unsigned int           nearest = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double excess = std::abs(local[d]) - half[d];
          if (excess > 0.)
            {
              inside     = false;
              outside[d] = std::copysign(excess, local[d]);
            }
          if (excess > std::abs(local[nearest]) - half[nearest])
            nearest = d;
        }
      normal = dealii::Tensor<1, dim>();
      if (!inside)
        {
          normal = outside / outside.norm();
          return outside.norm();
        }
      normal[nearest] = local[nearest] < 0. ? -1. : 1.;
      return std::abs(local[nearest]) - half[nearest];
    }



    /**
     * The signed distance from @p point to the boundary of the polygon
     * @p vertices (2D, either orientation), which contains @p point if
     * @p inside, and in @p normal the outward normal seen from there.
     */
    template <int dim>
    double
    polygon_distance(const std::vector<dealii::Point<dim>> &vertices,
                     const dealii::Point<dim>              &point,
                     const bool                             inside,
                     dealii::Tensor<1, dim>                &normal)
    {
      const unsigned int n = vertices.size();
      // Twice the signed area: positive if counterclockwise.
      double area = 0.;
      for (unsigned int i = 0, j = n - 1; i < n; j = i++)
        area +=
          vertices[j][0] * vertices[i][1] - vertices[i][0] * vertices[j][1];
      double nearest = std::numeric_limits<double>::max();
      normal         = dealii::Tensor<1, dim>();
      for (unsigned int i = 0, j = n - 1; i < n; j = i++)
        {
          const dealii::Tensor<1, dim> edge   = vertices[i] - vertices[j];
          const double                 length = edge.norm_square();
          if (length == 0.)
            continue;
          const double s =
            std::clamp((point - vertices[j]) * edge / length, 0., 1.);
          const dealii::Tensor<1, dim> away = point - (vertices[j] + s * edge);
          if (away.norm() >= nearest)
            continue;
          nearest = away.norm();
          if (nearest > 1e-12 * std::sqrt(length))
            normal = (inside ? -1. : 1.) * away / nearest;
          else
            {
              // On the edge (to round-off): its outward normal.
              normal[0] = edge[1];
              normal[1] = -edge[0];
              normal *= (area > 0. ? 1. : -1.) / std::sqrt(length);
            }
        }
      return inside ? -nearest : nearest;
    }
  } // namespace



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



  template <int dim>
  double
  signed_distance(const GrainParameters<dim> &grain,
                  const dealii::Point<dim>   &point,
                  dealii::Tensor<1, dim>     &normal)
  {
    switch (grain.shape)
      {
        case GrainShape::disk:
        case GrainShape::sphere:
          {
            const dealii::Tensor<1, dim> away   = point - grain.centre;
            const double                 length = away.norm();
            normal = length > 0. ? away / length : dealii::Tensor<1, dim>();
            return length - grain.radius;
          }
        case GrainShape::rectangle:
        case GrainShape::box:
          {
            dealii::Tensor<1, dim> local_normal;
            const double           distance =
              box_distance<dim>(0.5 * grain.size,
                                rotated<dim>(point - grain.centre,
                                             -grain.rotation),
                                local_normal);
            normal = rotated<dim>(local_normal, grain.rotation);
            return distance;
          }
        case GrainShape::polygon:
          return polygon_distance<dim>(grain.vertices,
                                       point,
                                       contains(grain, point),
                                       normal);
      }
    normal = dealii::Tensor<1, dim>();
    return 0.;
  }



  template <int dim>
  dealii::Tensor<1, dim>
  outward_normal(const GrainParameters<dim> &grain,
                 const dealii::Point<dim>   &point)
  {
    dealii::Tensor<1, dim> normal;
    signed_distance(grain, point, normal);
    return normal;
  }



  template bool
  contains<2>(const GrainParameters<2> &, const dealii::Point<2> &);
  template bool
  contains<3>(const GrainParameters<3> &, const dealii::Point<3> &);
  template std::pair<dealii::Point<2>, dealii::Point<2>>
  bounding_box<2>(const GrainParameters<2> &);
  template std::pair<dealii::Point<3>, dealii::Point<3>>
  bounding_box<3>(const GrainParameters<3> &);
  template double
  signed_distance<2>(const GrainParameters<2> &,
                     const dealii::Point<2> &,
                     dealii::Tensor<1, 2> &);
  template double
  signed_distance<3>(const GrainParameters<3> &,
                     const dealii::Point<3> &,
                     dealii::Tensor<1, 3> &);
  template dealii::Tensor<1, 2>
  outward_normal<2>(const GrainParameters<2> &, const dealii::Point<2> &);
  template dealii::Tensor<1, 3>
  outward_normal<3>(const GrainParameters<3> &, const dealii::Point<3> &);
} // namespace grainmpm
