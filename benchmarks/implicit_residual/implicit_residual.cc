// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Implicit residual benchmark (doc/validation.md, Solver cost): the block
// of the explicit benchmark (1,048,576 material points on 512^2 cells,
// 4 x 4 per cell) with a shear velocity field, one implicit theta = 1/2
// step at CFL 2. Prints
//  - ns/particle of one residual evaluation of ThetaResidual, next to a
//    plain-array residual of the same work (the same cached shape function
//    gradients and slots in flat arrays, the same Jaumann linear elastic
//    update written out by hand) in the same process; goal <= 1.5;
//  - residual evaluations per Krylov iteration including all overhead of
//    Newton-GMRES (orthogonalisation, preconditioner, vector updates):
//    1 + (solve time - evaluations x residual time) / (Krylov iterations x
//    residual time); goal <= 1.6.
// The mass matrix is the lumped one unless the fifth argument says
// `blended` (the implicit default); the plain residual always has the
// lumped mass, so with `blended` the ratio is the cost of the consistent
// part, and the difference of the results is not printed.
//
// Usage: implicit_residual [n_cells=512] [particles_per_direction=4]
//                          [evaluations=10] [shape functions=linear]
//                          [mass matrix=lumped]

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/implicit_theta.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <iostream>

#include "../common/elastic_block.h"

using namespace grainmpm;
using VectorType = LinearAlgebra::distributed::Vector<double>;

namespace
{
  double
  seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
      .count();
  }



  /**
   * The plain-array residual: flat arrays in cache order, the Jaumann
   * linear elastic update (plane strain) and the force scatter written out,
   * R = V - v_n - dt f / m.
   */
  struct PlainResidual
  {
    std::vector<unsigned int> first_entry; // entries of each particle
    std::vector<unsigned int> slots;
    std::vector<double>       gradients; // 2 per entry
    std::vector<double>       stresses;  // xx, yy, zz, xy per particle
    std::vector<double>       volumes;
    std::vector<double>       masses;
    std::vector<double>       old_velocities;
    double                    lambda, mu, theta, dt;

    mutable std::vector<double> theta_v, forces;

    void
    evaluate(const std::vector<double> &V, std::vector<double> &R) const
    {
      const std::size_t n = V.size();
      theta_v.resize(n);
      forces.assign(n, 0.);
      for (std::size_t k = 0; k < n; ++k)
        theta_v[k] = (1. - theta) * old_velocities[k] + theta * V[k];
      const std::size_t n_particles = volumes.size();
      for (std::size_t p = 0; p < n_particles; ++p)
        {
          const unsigned int *s     = slots.data();
          const double       *G     = gradients.data();
          const unsigned int  begin = first_entry[p], end = first_entry[p + 1];
          double              L00 = 0., L01 = 0., L10 = 0., L11 = 0.;
          for (unsigned int v = begin; v < end; ++v)
            {
              const double vx = theta_v[2 * s[v]], vy = theta_v[2 * s[v] + 1];
              L00 += vx * G[2 * v];
              L01 += vx * G[2 * v + 1];
              L10 += vy * G[2 * v];
              L11 += vy * G[2 * v + 1];
            }
          L00 *= dt, L01 *= dt, L10 *= dt, L11 *= dt;
          const double *sig = &stresses[4 * p];
          const double  exy = 0.5 * (L01 + L10), w = 0.5 * (L01 - L10);
          const double  tr = L00 + L11;
          // Jaumann: sigma + W sigma - sigma W (in-plane spin w).
          const double sxx = sig[0] + 2. * w * sig[3],
                       syy = sig[1] - 2. * w * sig[3],
                       sxy = sig[3] + w * (sig[1] - sig[0]);
          const double nxx = sxx + 2. * mu * L00 + lambda * tr,
                       nyy = syy + 2. * mu * L11 + lambda * tr,
                       nxy = sxy + 2. * mu * exy;
          const double txx = (1. - theta) * sig[0] + theta * nxx,
                       tyy = (1. - theta) * sig[1] + theta * nyy,
                       txy = (1. - theta) * sig[3] + theta * nxy;
          const double J   = (1. + L00) * (1. + L11) - L01 * L10;
          const double vol = volumes[p] * ((1. - theta) + theta * J);
          for (unsigned int v = begin; v < end; ++v)
            {
              forces[2 * s[v]] -= vol * (txx * G[2 * v] + txy * G[2 * v + 1]);
              forces[2 * s[v] + 1] -=
                vol * (txy * G[2 * v] + tyy * G[2 * v + 1]);
            }
        }
      R.resize(n);
      for (std::size_t k = 0; k < n; ++k)
        R[k] = V[k] - old_velocities[k] - dt * forces[k] / masses[k / 2];
    }
  };
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int n_cells = argc > 1 ? std::stoi(argv[1]) : 512;
  const unsigned int per_dir = argc > 2 ? std::stoi(argv[2]) : 4;
  const unsigned int n_evals = argc > 3 ? std::stoi(argv[3]) : 10;
  const std::string  kernel  = argc > 4 ? argv[4] : "linear";
  const std::string  mass    = argc > 5 ? argv[5] : "lumped";
  const double       lambda  = benchmarks::ElasticBlock::lambda;
  const double       mu      = benchmarks::ElasticBlock::mu;
  const double       dt = 2. / n_cells / benchmarks::ElasticBlock::wave_speed();

  benchmarks::ElasticBlock block(
    n_cells,
    per_dir,
    "0.1*sin(20*y); 0.1*cos(20*x)",
    dt,
    "subsection Time stepping\n  set Scheme = implicit theta\n"
    "  set Mass matrix = " +
      mass +
      "\nend\n"
      "subsection Nonlinear solver\n  set Forcing term = constant\n"
      "  set Forcing constant = 1e-6\n  set Tolerance = 1e-8\nend\n"
      "subsection Material points\n  set Shape functions = " +
      kernel + "\nend\n");
  auto       &particle_handler = *block.particle_handler;
  const auto &grid             = *block.grid;
  block.move_off_arrangement();
  ImplicitTheta<2> stepper(block.parameters,
                           grid,
                           block.grains,
                           block.materials);
  const double     n_particles = particle_handler.n_global_particles();

  // grainmpm's residual.
  auto      &residual = stepper.prepare(particle_handler, 0., dt);
  VectorType V(stepper.get_old_velocities()), R(V);
  V *= 1.01;
  residual.evaluate(V, R); // warm-up
  auto start = std::chrono::steady_clock::now();
  for (unsigned int e = 0; e < n_evals; ++e)
    residual.evaluate(V, R);
  const double residual_seconds = seconds_since(start) / n_evals;

  // The plain residual on the same data.
  PlainResidual       plain;
  TransferCache<2>    cache;
  GrainFieldLayout<2> layout;
  cache.reinit(grid,
               particle_handler,
               {0},
               block.parameters.material_points.shape_functions,
               Tensor<1, 2>(
                 {0.5 / n_cells / per_dir, 0.5 / n_cells / per_dir}));
  layout.reinit(cache, grid);
  plain.first_entry = cache.first_entry;
  plain.slots       = cache.slots;
  for (const auto &G : cache.shape_gradients)
    {
      plain.gradients.push_back(G[0]);
      plain.gradients.push_back(G[1]);
    }
  for_each_particle(grid, particle_handler, [&](const auto &, const auto &p) {
    const auto properties = p->get_properties();
    const auto stress     = MaterialPointLayout<2>::get_stress(properties);
    plain.stresses.insert(
      plain.stresses.end(),
      {stress[0][0], stress[1][1], stress[2][2], stress[0][1]});
    plain.volumes.push_back(properties[MaterialPointLayout<2>::volume]);
  });
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    plain.masses.push_back(stepper.get_masses().local_element(s));
  for (unsigned int k = 0; k < V.size(); ++k)
    plain.old_velocities.push_back(
      stepper.get_old_velocities().local_element(k));
  plain.lambda = lambda, plain.mu = mu, plain.theta = 0.5, plain.dt = dt;
  std::vector<double> plain_V(V.begin(), V.end()), plain_R;
  plain.evaluate(plain_V, plain_R);
  double difference = 0.;
  for (unsigned int k = 0; k < V.size(); ++k)
    difference =
      std::max(difference, std::abs(plain_R[k] - R.local_element(k)));
  start = std::chrono::steady_clock::now();
  for (unsigned int e = 0; e < n_evals; ++e)
    plain.evaluate(plain_V, plain_R);
  const double plain_seconds = seconds_since(start) / n_evals;

  // A whole Newton-Krylov solve from v^n.
  VectorType          x(stepper.get_old_velocities());
  const unsigned long evaluations_before = residual.n_residual_evaluations();
  start                                  = std::chrono::steady_clock::now();
  const NewtonStatistics newton = stepper.get_solver().solve(residual, x);
  const double           solve_seconds = seconds_since(start);
  const double           evaluations =
    residual.n_residual_evaluations() - evaluations_before;
  const double per_krylov =
    1. + (solve_seconds - evaluations * residual_seconds) /
           (newton.linear_iterations * residual_seconds);

  std::cout << "implicit residual benchmark: " << n_cells << "^2 cells, "
            << kernel << " shape functions, " << mass << " mass matrix, "
            << static_cast<unsigned long>(n_particles) << " material points, "
            << V.size() << " unknowns, CFL 2\n"
            << "  grainmpm ThetaResidual:  "
            << 1e9 * residual_seconds / n_particles << " ns/particle\n"
            << "  plain-array residual:    "
            << 1e9 * plain_seconds / n_particles << " ns/particle"
            << (mass == "lumped" ?
                  " (max |difference| " + std::to_string(difference) + ")" :
                  std::string(" (lumped mass)"))
            << "\n"
            << "  ratio:                   " << residual_seconds / plain_seconds
            << " (goal <= 1.5)\n"
            << "  Newton-Krylov solve:     " << newton.iterations << " Newton, "
            << newton.linear_iterations << " Krylov iterations, " << evaluations
            << " residual evaluations, " << solve_seconds
            << " s, converged: " << (newton.converged ? "yes" : "no") << "\n"
            << "  residual evaluations per Krylov iteration incl. overhead: "
            << per_krylov << " (goal <= 1.6)\n";
  return 0;
}
