// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/step_error_estimator.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

#include <cmath>

namespace grainmpm
{
  template <int dim>
  StepErrorEstimator<dim>::StepErrorEstimator(
    const std::vector<GrainInfo<dim>> &grains)
  {
    for (const auto &grain : grains)
      deformable.push_back(!grain.rigid);
  }



  template <int dim>
  void
  StepErrorEstimator<dim>::record_velocities(
    const Particles::ParticleHandler<dim> &particle_handler)
  {
    using Layout = MaterialPointLayout<dim>;
    velocities.clear();
    velocities.reserve(particle_handler.n_locally_owned_particles());
    for (const auto &particle : particle_handler)
      velocities.push_back(Layout::get_velocity(particle.get_properties()));
  }



  template <int dim>
  double
  StepErrorEstimator<dim>::estimate(
    Particles::ParticleHandler<dim> &particle_handler,
    const double                     dt,
    const MPI_Comm                   communicator)
  {
    using Layout = MaterialPointLayout<dim>;
    AssertDimension(velocities.size(),
                    particle_handler.n_locally_owned_particles());
    // Delta a of one step dt from the change between the mid-points of
    // the last step and this one.
    const double scale =
      last_step > 0. ? 2. * dt / (dt + last_step) * dt * dt / 12. : 0.;
    double      sums[2] = {0., 0.};
    std::size_t k       = 0;
    for (auto &particle : particle_handler)
      {
        const ArrayView<double> properties = particle.get_properties();
        const Tensor<1, dim>    old_v      = velocities[k++];
        if (!deformable[Layout::get_grain(properties)])
          continue;
        const Tensor<1, dim> v = Layout::get_velocity(properties);
        const Tensor<1, dim> a = (v - old_v) / dt;
        const double         m = properties[Layout::mass];
        sums[0] +=
          m *
          (scale * (a - Layout::get_acceleration(properties))).norm_square();
        sums[1] += m * (0.5 * dt * (v + old_v)).norm_square();
        Layout::set_acceleration(a, properties);
      }
    Utilities::MPI::sum(ArrayView<const double>(sums, 2),
                        communicator,
                        ArrayView<double>(sums, 2));
    const bool has_history = last_step > 0.;
    last_step              = dt;
    velocities.clear();
    if (!has_history || !(sums[1] > 0.))
      return -1.;
    return std::sqrt(sums[0] / sums[1]);
  }



  template class StepErrorEstimator<2>;
  template class StepErrorEstimator<3>;
} // namespace grainmpm
