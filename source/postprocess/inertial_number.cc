// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/inertial_number.h>
#include <grainmpm/transfer/rigid_grain_motion.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainmpm
{
  template <int dim>
  InertialNumber<dim>::InertialNumber(
    const std::vector<GrainInfo<dim>>     &grains,
    const std::vector<unsigned int>       &rigid_grains,
    const Particles::ParticleHandler<dim> &particle_handler,
    const MPI_Comm                         communicator)
    : grains(grains)
    , rigid_grains(rigid_grains)
    , communicator(communicator)
  {
    if (rigid_grains.empty())
      return;
    // Per grain: mass and initial volume (unchanged over a run, so that a
    // resumed run gets the same d and rho).
    using Layout = MaterialPointLayout<dim>;
    std::vector<double> sums(2 * grains.size(), 0.);
    for (const auto &particle : particle_handler)
      {
        const auto         properties = particle.get_properties();
        const unsigned int g          = Layout::get_grain(properties);
        sums[2 * g] += properties[Layout::mass];
        sums[2 * g + 1] += properties[Layout::initial_volume];
      }
    Utilities::MPI::sum(sums, communicator, sums);
    double       mass = 0., volume = 0., diameters = 0.;
    unsigned int n = 0;
    for (unsigned int g = 0; g < grains.size(); ++g)
      if (!grains[g].rigid && sums[2 * g + 1] > 0.)
        {
          mass += sums[2 * g];
          volume += sums[2 * g + 1];
          // The diameter of the disk (sphere) of the grain's area (volume).
          diameters +=
            (dim == 2 ? 2. * std::sqrt(sums[2 * g + 1] / numbers::PI) :
                        std::cbrt(6. * sums[2 * g + 1] / numbers::PI));
          ++n;
        }
    if (n > 0)
      {
        diameter = diameters / n;
        density  = mass / volume;
      }
  }



  template <int dim>
  void
  InertialNumber<dim>::measure(
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<Tensor<1, dim>>     &directions)
  {
    // Minima as maxima of the negative.
    const unsigned int n_rigid = rigid_grains.size();
    std::vector<int>   rigid_index(grains.size(), -1);
    for (unsigned int r = 0; r < n_rigid; ++r)
      rigid_index[rigid_grains[r]] = r;
    const double lowest = -std::numeric_limits<double>::max();
    extents.assign(2 * dim + 2 * n_rigid, lowest);
    using Layout = MaterialPointLayout<dim>;
    for (const auto &particle : particle_handler)
      {
        const Point<dim>  &x = particle.get_location();
        const unsigned int g = Layout::get_grain(particle.get_properties());
        if (grains[g].rigid)
          {
            const int r = rigid_index[g];
            if (r >= 0)
              extents[2 * dim + 2 * r + 1] =
                std::max(extents[2 * dim + 2 * r + 1], directions[r] * x);
            continue;
          }
        for (unsigned int d = 0; d < dim; ++d)
          {
            extents[2 * d]     = std::max(extents[2 * d], x[d]);
            extents[2 * d + 1] = std::max(extents[2 * d + 1], -x[d]);
          }
        for (unsigned int r = 0; r < n_rigid; ++r)
          extents[2 * dim + 2 * r] =
            std::max(extents[2 * dim + 2 * r], directions[r] * x);
      }
    Utilities::MPI::max(extents, communicator, extents);
  }



  template <int dim>
  std::vector<double>
  InertialNumber<dim>::compute(
    const unsigned int                     step,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<Tensor<1, dim>>     &forces,
    const std::vector<Point<dim>>         &centres,
    const double                           time)
  {
    const unsigned int  n_rigid = rigid_grains.size();
    std::vector<double> numbers(n_rigid, 0.);
    if (n_rigid == 0)
      return numbers;

    // The direction u of each rigid grain's motion.
    std::vector<Tensor<1, dim>> directions(n_rigid);
    std::vector<double>         speeds(n_rigid);
    for (unsigned int r = 0; r < n_rigid; ++r)
      {
        const Tensor<1, dim> velocity =
          RigidGrainMotion<dim>::velocity(grains[rigid_grains[r]],
                                          centres[r],
                                          time);
        speeds[r] = velocity.norm();
        if (speeds[r] > 0.)
          directions[r] = velocity / speeds[r];
      }
    if (extents.empty() || step % refresh_interval == 0)
      measure(particle_handler, directions);

    for (unsigned int r = 0; r < n_rigid; ++r)
      {
        if (speeds[r] == 0.)
          continue;
        const double height =
          extents[2 * dim + 2 * r] - extents[2 * dim + 2 * r + 1];
        // The extent across u: the box in the other coordinates.
        unsigned int along = 0;
        for (unsigned int d = 1; d < dim; ++d)
          if (std::abs(directions[r][d]) > std::abs(directions[r][along]))
            along = d;
        double area = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          if (d != along)
            area *= std::max(0., extents[2 * d] + extents[2 * d + 1]);
        const double pressure =
          area > 0. ? std::max(0., -(forces[r] * directions[r])) / area : 0.;
        if (pressure > 0. && height > 0. && density > 0.)
          numbers[r] =
            speeds[r] / height * diameter / std::sqrt(pressure / density);
        else
          numbers[r] = std::numeric_limits<double>::infinity();
      }
    return numbers;
  }



  template class InertialNumber<2>;
  template class InertialNumber<3>;
} // namespace grainmpm
