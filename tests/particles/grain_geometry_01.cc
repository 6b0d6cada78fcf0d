// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// outward_normal(): the outward unit normal of a grain's shape seen from a
// point, inside and outside, for a disk, a rectangle rotated by 30 degrees,
// a triangle given in either orientation, a sphere and a box rotated about
// z. Each line prints the normal and the one worked out by hand (a point on
// a face to round-off gets that face's normal); the lines "lattice points"
// check, on a lattice around the rectangle and the triangle, that the
// normal is the gradient of the signed distance: a step of 0.01 along it
// changes the distance to the boundary by 0.01; and that signed_distance()
// is the distance the rays find, negative inside.

#include <grainmpm/particles/grain_geometry.h>

#include <deal.II/base/mpi.h>

#include <iomanip>

#include "../tests.h"

using namespace dealii;
using namespace grainmpm;

template <int dim>
void
print(const std::string          &what,
      const GrainParameters<dim> &grain,
      const Point<dim>           &point,
      const Tensor<1, dim>       &expected)
{
  const Tensor<1, dim> normal = outward_normal(grain, point);
  deallog << what << ": n = (" << std::fixed << std::setprecision(4);
  for (unsigned int d = 0; d < dim; ++d)
    deallog << (d > 0 ? ", " : "") << filter_out_small_numbers(normal[d]);
  deallog << "), |n - expected| = " << std::scientific << std::setprecision(1)
          << filter_out_small_numbers((normal - expected).norm()) << std::endl;
}



// The distance from @p point to the boundary of @p grain, found
// independently of outward_normal(): along rays from @p point in 1440
// directions, the first change of contains() (marched in steps of 0.002 up
// to 0.5, then bisected), the shortest of them.
double
distance_to_boundary(const GrainParameters<2> &grain, const Point<2> &point)
{
  const bool inside  = contains(grain, point);
  double     nearest = 1e300;
  for (unsigned int i = 0; i < 1440; ++i)
    {
      const double       angle = 2. * M_PI * i / 1440.;
      const Tensor<1, 2> direction({std::cos(angle), std::sin(angle)});
      double             low = 0., high = 0.;
      for (unsigned int k = 1; k <= 250 && high == 0.; ++k)
        if (contains(grain, point + 0.002 * k * direction) != inside)
          {
            low  = 0.002 * (k - 1);
            high = 0.002 * k;
          }
      if (high == 0. || low >= nearest)
        continue;
      for (unsigned int k = 0; k < 40; ++k)
        {
          const double middle = 0.5 * (low + high);
          if (contains(grain, point + middle * direction) == inside)
            low = middle;
          else
            high = middle;
        }
      nearest = std::min(nearest, low);
    }
  return inside ? -nearest : nearest;
}



void
check_gradient(const std::string &what, const GrainParameters<2> &grain)
{
  // A lattice of points around the shape, skipping those within a step of
  // the medial axis (where the two one-sided differences disagree): there
  // a step of 0.01 along n must change the signed distance by 0.01 (to
  // 1e-2: the rays find the distance to a corner to about 1e-4).
  const auto [lower, upper] = bounding_box(grain);
  double       worst = 0., worst_distance = 0.;
  unsigned int n_checked = 0;
  const double step      = 1e-2;
  for (unsigned int i = 0; i <= 8; ++i)
    for (unsigned int j = 0; j <= 8; ++j)
      {
        Point<2> point;
        for (unsigned int d = 0; d < 2; ++d)
          point[d] = lower[d] - 0.1 +
                     (upper[d] - lower[d] + 0.2) * (d == 0 ? i : j) / 8.;
        const Tensor<1, 2> normal = outward_normal(grain, point);
        const double       here   = distance_to_boundary(grain, point);
        Tensor<1, 2>       unused;
        worst_distance =
          std::max(worst_distance,
                   std::abs(signed_distance(grain, point, unused) - here));
        const double forward =
          distance_to_boundary(grain, point + step * normal);
        const double backward =
          distance_to_boundary(grain, point - step * normal);
        if (std::abs((forward - here) - (here - backward)) > 1e-3 * step)
          continue;
        worst =
          std::max(worst, std::abs((forward - backward) / (2. * step) - 1.));
        ++n_checked;
      }
  deallog << what << ": " << (n_checked > 40 ? "more than 40" : "too few")
          << " lattice points, d(distance)/ds along n - 1 "
          << (worst < 1e-2 ? "below 1e-2" : "too large")
          << "; signed_distance() - the rays' distance "
          << (worst_distance < 1e-3 ? "below 1e-3" : "too large") << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  GrainParameters<2> disk;
  disk.shape  = GrainShape::disk;
  disk.centre = Point<2>(0.3, 0.3);
  disk.radius = 0.2;
  print<2>("disk, outside", disk, Point<2>(0.6, 0.7), Tensor<1, 2>({0.6, 0.8}));
  print<2>("disk, inside", disk, Point<2>(0.3, 0.35), Tensor<1, 2>({0., 1.}));
  print<2>("disk, centre", disk, Point<2>(0.3, 0.3), Tensor<1, 2>());

  GrainParameters<2> rectangle;
  rectangle.shape    = GrainShape::rectangle;
  rectangle.centre   = Point<2>(0.5, 0.5);
  rectangle.size     = Tensor<1, 2>({0.4, 0.2});
  rectangle.rotation = 30.;
  const Tensor<1, 2> e1({std::cos(M_PI / 6.), std::sin(M_PI / 6.)});
  const Tensor<1, 2> e2({-std::sin(M_PI / 6.), std::cos(M_PI / 6.)});
  const Point<2>     c = rectangle.centre;
  print<2>("rectangle, inside near a long face",
           rectangle,
           c + 0.05 * e1 + 0.08 * e2,
           e2);
  print<2>("rectangle, inside near a short face",
           rectangle,
           c - 0.18 * e1 + 0.01 * e2,
           -e1);
  print<2>("rectangle, outside a short face", rectangle, c + 0.25 * e1, e1);
  print<2>("rectangle, outside a corner",
           rectangle,
           c + 0.3 * e1 - 0.2 * e2,
           (e1 - e2) / std::sqrt(2.));

  for (const bool counterclockwise : {true, false})
    {
      GrainParameters<2> triangle;
      triangle.shape = GrainShape::polygon;
      triangle.vertices =
        counterclockwise ?
          std::vector<Point<2>>{{0.1, 0.1}, {0.6, 0.1}, {0.1, 0.6}} :
          std::vector<Point<2>>{{0.1, 0.1}, {0.1, 0.6}, {0.6, 0.1}};
      const std::string name = counterclockwise ?
                                 "triangle (counterclockwise)" :
                                 "triangle (clockwise)";
      print<2>(name + ", below",
               triangle,
               Point<2>(0.35, 0.),
               Tensor<1, 2>({0., -1.}));
      print<2>(name + ", inside",
               triangle,
               Point<2>(0.2, 0.25),
               Tensor<1, 2>({-1., 0.}));
      print<2>(name + ", on the hypotenuse",
               triangle,
               Point<2>(0.175, 0.525),
               Tensor<1, 2>({1., 1.}) / std::sqrt(2.));
      print<2>(name + ", on an edge",
               triangle,
               Point<2>(0.35, 0.1),
               Tensor<1, 2>({0., -1.}));
      print<2>(name + ", beyond the hypotenuse",
               triangle,
               Point<2>(0.5, 0.5),
               Tensor<1, 2>({1., 1.}) / std::sqrt(2.));
      print<2>(name + ", beyond a corner",
               triangle,
               Point<2>(0., 0.),
               Tensor<1, 2>({-1., -1.}) / std::sqrt(2.));
      check_gradient(name, triangle);
    }
  check_gradient("rectangle", rectangle);

  GrainParameters<3> sphere;
  sphere.shape  = GrainShape::sphere;
  sphere.centre = Point<3>(0.5, 0.5, 0.5);
  sphere.radius = 0.2;
  print<3>("sphere, outside",
           sphere,
           Point<3>(0.5, 0.8, 0.9),
           Tensor<1, 3>({0., 0.6, 0.8}));

  GrainParameters<3> box;
  box.shape    = GrainShape::box;
  box.centre   = Point<3>(0.5, 0.5, 0.5);
  box.size     = Tensor<1, 3>({0.4, 0.2, 0.3});
  box.rotation = 30.;
  const Tensor<1, 3> f1({std::cos(M_PI / 6.), std::sin(M_PI / 6.), 0.});
  const Tensor<1, 3> f2({-std::sin(M_PI / 6.), std::cos(M_PI / 6.), 0.});
  const Tensor<1, 3> f3({0., 0., 1.});
  print<3>("box, inside near the top",
           box,
           box.centre + 0.05 * f1 + 0.02 * f2 + 0.13 * f3,
           f3);
  print<3>("box, inside near a side",
           box,
           box.centre + 0.05 * f1 - 0.09 * f2,
           -f2);
  print<3>("box, outside an edge",
           box,
           box.centre + 0.3 * f1 + 0.25 * f3,
           (f1 + f3) / std::sqrt(2.));
}
