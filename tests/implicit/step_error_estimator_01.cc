// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// StepErrorEstimator: eta of a step against the formula computed by hand
// for points whose accelerations change from one step to the next (steps
// of different lengths, points of different masses, a rigid point that
// must be left out); no estimate at the first step and after forget();
// zero for accelerations that do not change.

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/step_error_estimator.h>

#include <deal.II/base/mpi.h>

#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>

#include "../tests.h"

using namespace grainmpm;

template <int dim>
Tensor<1, dim>
vector_of(const double a, const double b, const double c)
{
  Tensor<1, dim> v;
  const double   values[3] = {a, b, c};
  for (unsigned int d = 0; d < dim; ++d)
    v[d] = values[d];
  return v;
}



// Give every point the velocity v + dt a(p), a(p) from @p acceleration.
template <int dim, class Function>
void
accelerate(Particles::ParticleHandler<dim> &particle_handler,
           const double                     dt,
           const Function                  &acceleration)
{
  for (auto &particle : particle_handler)
    {
      const auto properties = particle.get_properties();
      MaterialPointLayout<dim>::set_velocity(
        MaterialPointLayout<dim>::get_velocity(properties) +
          dt * acceleration(particle.get_id()),
        properties);
    }
}



template <int dim>
void
test()
{
  using Layout = MaterialPointLayout<dim>;
  deallog << "dim = " << dim << std::endl;
  Triangulation<dim> triangulation;
  GridGenerator::hyper_cube(triangulation, 0., 1.);
  triangulation.refine_global(2);
  MappingQ<dim>                   mapping(1);
  Particles::ParticleHandler<dim> particle_handler(triangulation,
                                                   mapping,
                                                   Layout::n_properties);

  // Points 0..3 in grain 0 (deformable), point 4 in grain 1 (rigid).
  const unsigned int  n = 5;
  std::vector<double> masses{1., 2., 0.5, 3., 7.};
  for (unsigned int p = 0; p < n; ++p)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = 0.1 + 0.17 * p + 0.05 * d;
      std::vector<double> properties(Layout::n_properties, 0.);
      properties[Layout::mass]  = masses[p];
      properties[Layout::grain] = p < 4 ? 0. : 1.;
      Layout::set_velocity(vector_of<dim>(0.1 * p, -0.2, 0.05 * p),
                           make_array_view(properties));
      const auto cell =
        GridTools::find_active_cell_around_point(mapping, triangulation, x);
      particle_handler.insert_particle(
        x, cell.second, p, cell.first, make_array_view(properties));
    }

  std::vector<GrainInfo<dim>> grains(2);
  grains[1].rigid = true;
  StepErrorEstimator<dim> estimator(grains);

  const auto first = [](const types::particle_index p) {
    return vector_of<dim>(1. + p, -0.5 * p, 0.3);
  };
  const auto second = [](const types::particle_index p) {
    return p < 4 ? vector_of<dim>(1.5 + p * p, 0.2, -0.1 * p) :
                   vector_of<dim>(100., -300., 50.);
  };

  // Step 1: no estimate yet.
  const double dt1 = 0.1;
  estimator.record_velocities(particle_handler);
  accelerate(particle_handler, dt1, first);
  const double eta1 = estimator.estimate(particle_handler, dt1, MPI_COMM_WORLD);
  deallog << "no estimate at the first step: " << (eta1 < 0. ? "yes" : "no")
          << std::endl;

  // Step 2, another length: eta by hand (velocities before and after).
  const double                dt2 = 0.25;
  std::vector<Tensor<1, dim>> before(n), after(n);
  for (const auto &particle : particle_handler)
    before[particle.get_id()] = Layout::get_velocity(particle.get_properties());
  estimator.record_velocities(particle_handler);
  accelerate(particle_handler, dt2, second);
  for (const auto &particle : particle_handler)
    after[particle.get_id()] = Layout::get_velocity(particle.get_properties());
  const double eta2 = estimator.estimate(particle_handler, dt2, MPI_COMM_WORLD);
  double       error = 0., displacement = 0.;
  for (unsigned int p = 0; p < 4; ++p)
    {
      const Tensor<1, dim> change =
        (second(p) - first(p)) * 2. * dt2 / (dt1 + dt2) * dt2 * dt2 / 12.;
      error += masses[p] * change.norm_square();
      displacement +=
        masses[p] * (0.5 * dt2 * (before[p] + after[p])).norm_square();
    }
  const double expected = std::sqrt(error / displacement);
  deallog << "eta of the second step: " << eta2 << std::endl;
  deallog << "as computed by hand: "
          << (std::abs(eta2 - expected) < 1e-12 * expected ? "yes" : "no")
          << std::endl;

  // Step 3: the same accelerations again, no error.
  estimator.record_velocities(particle_handler);
  accelerate(particle_handler, 0.1, second);
  const double eta3 = estimator.estimate(particle_handler, 0.1, MPI_COMM_WORLD);
  deallog << "zero for unchanged accelerations: "
          << (eta3 >= 0. && eta3 < 1e-12 ? "yes" : "no") << std::endl;

  // After forget(): no estimate.
  estimator.forget();
  estimator.record_velocities(particle_handler);
  accelerate(particle_handler, 0.1, first);
  deallog << "no estimate after forget(): "
          << (estimator.estimate(particle_handler, 0.1, MPI_COMM_WORLD) < 0. ?
                "yes" :
                "no")
          << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
