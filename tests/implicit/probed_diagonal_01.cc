// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The diagonal of the Jacobian probed with 18 coloured residual
// evaluations (doc/theory.md section 11):
// 1. without contact it equals the analytic diagonal of an unstressed
//    elastic grain,
//    1 + theta^2 dt^2 sum_p V_p [(lambda + 2 mu) G_d^2 + mu G_e^2] / m;
// 2. with two grains in frictional contact it equals the diagonal of the
//    simplified Jacobian probed one unknown at a time (so the colouring
//    is exact also at contact nodes).
// Both with the linear and with the uGIMP shape functions (a point touches
// up to 3 nodes per axis: the period 3 of the colours is still exact), with
// the lumped and with the blended mass matrix (whose consistent part couples
// the same slots as the stiffness and adds alpha (sum_p m_p S_ip^2 / m_i - 1)
// to the diagonal), on points moved off their regular arrangement.

#include "../tests.h"

#include "../implicit_fixture.h"
#include "elastic_block.h"

using namespace grainmpm;
using VectorType = LinearAlgebra::distributed::Vector<double>;

double
max_relative_difference(const VectorType &a, const VectorType &b)
{
  double difference = 0.;
  for (unsigned int k = 0; k < a.size(); ++k)
    difference = std::max(difference,
                          std::abs(a.local_element(k) - b.local_element(k)) /
                            std::abs(b.local_element(k)));
  return difference;
}



std::string
kernel_text(const std::string &kernel, const std::string &mass_matrix)
{
  return "subsection Material points\n  set Shape functions = " + kernel +
         "\nend\nsubsection Time stepping\n  set Mass matrix = " + mass_matrix +
         "\nend\n";
}



void
check_analytic_diagonal(const std::string &kernel,
                        const std::string &mass_matrix)
{
  deallog << "Shape functions = " << kernel << ", Mass matrix = " << mass_matrix
          << std::endl;
  ImplicitFixture<2> fixture(elastic_block_parameters(
                               kernel_text(kernel, mass_matrix)),
                             "probed_diagonal_01");
  jitter(fixture);
  auto        &stepper  = *fixture.stepper;
  const double dt       = fixture.parameters.time_stepping.time_step;
  const double theta    = fixture.parameters.time_stepping.theta;
  auto        &residual = stepper.prepare(*fixture.particle_handler, 0., dt);
  const VectorType &V   = stepper.get_old_velocities();

  const unsigned long before = residual.n_residual_evaluations();
  VectorType          diagonal;
  residual.jacobian_diagonal(
    V,
    [&](const VectorType &x, const VectorType &z) {
      return stepper.get_solver().differencing_step(x, z);
    },
    diagonal);
  deallog << "residual evaluations for the diagonal: "
          << residual.n_residual_evaluations() - before << std::endl;

  // The analytic diagonal from the cached gradients.
  TransferCache<2>    cache;
  GrainFieldLayout<2> layout;
  const Tensor<1, 2>  half_width({0.025, 0.025}); // h / 4
  cache.reinit(*fixture.grid,
               *fixture.particle_handler,
               {0},
               fixture.parameters.material_points.shape_functions,
               half_width);
  layout.reinit(cache, *fixture.grid);
  VectorType stiffness(V), mass_diagonal(V);
  stiffness     = 0.;
  mass_diagonal = 0.;
  std::size_t p = 0;
  for_each_particle(
    *fixture.grid,
    *fixture.particle_handler,
    [&](const auto &, const auto &particle) {
      const double volume =
        particle->get_properties()[MaterialPointLayout<2>::volume];
      const double mass =
        particle->get_properties()[MaterialPointLayout<2>::mass];
      for (unsigned int v = cache.first_entry[p]; v < cache.first_entry[p + 1];
           ++v)
        {
          const auto  &G    = cache.shape_gradients[v];
          const auto   slot = cache.slots[v];
          const double S    = cache.shape_values[v];
          for (unsigned int d = 0; d < 2; ++d)
            mass_diagonal.local_element(2 * slot + d) += mass * S * S;
          stiffness.local_element(2 * slot) +=
            volume * ((block_lambda + 2. * block_mu) * G[0] * G[0] +
                      block_mu * G[1] * G[1]);
          stiffness.local_element(2 * slot + 1) +=
            volume * ((block_lambda + 2. * block_mu) * G[1] * G[1] +
                      block_mu * G[0] * G[0]);
        }
      ++p;
    });
  // With the blended mass matrix M = (1 - alpha) M_L + alpha M_C the
  // diagonal of M_L^-1 M is 1 - alpha + alpha sum_p m_p S_ip^2 / m_i.
  VectorType   analytic(V);
  double       largest_stiffness_ratio = 0.;
  const double alpha =
    fixture.parameters.time_stepping.consistent_mass_fraction;
  for (unsigned int k = 0; k < V.size(); ++k)
    {
      const double m = stepper.get_masses().local_element(k / 2);
      const double ratio =
        theta * theta * dt * dt * stiffness.local_element(k) / m;
      analytic.local_element(k) =
        1. - alpha + alpha * mass_diagonal.local_element(k) / m + ratio;
      largest_stiffness_ratio = std::max(largest_stiffness_ratio, ratio);
    }
  const double difference = max_relative_difference(diagonal, analytic);
  deallog << "largest theta^2 dt^2 K_ii / m_i > 1: "
          << (largest_stiffness_ratio > 1. ? "yes" : "no") << std::endl;
  deallog << "probed = analytic diagonal (max relative difference < 1e-6): "
          << (difference < 1e-6 ? "yes" : "no") << std::endl;
  if (difference >= 1e-6)
    deallog << "  max relative difference = " << difference << std::endl;
}



void
check_contact_diagonal(const std::string &kernel,
                       const std::string &mass_matrix)
{
  const std::string text =
    two_grains_in_contact_parameters(kernel_text(kernel, mass_matrix));
  ImplicitFixture<2> fixture(text, "probed_diagonal_01_contact");
  jitter(fixture);
  auto &stepper       = *fixture.stepper;
  auto &residual      = stepper.prepare(*fixture.particle_handler, 0., 5.45e-3);
  const VectorType &V = stepper.get_old_velocities();
  deallog << "contact nodes: " << stepper.get_layout().contact_nodes().size()
          << std::endl;
  VectorType                 projected(V);
  std::vector<unsigned char> flags(fixture.grid->n_nodes(), 0);
  deallog << "nodes with active contact: "
          << residual.project(V, projected, &flags) << std::endl;

  const auto step = [&](const VectorType &x, const VectorType &z) {
    return stepper.get_solver().differencing_step(x, z);
  };
  VectorType diagonal;
  residual.jacobian_diagonal(V, step, diagonal);

  // One unknown at a time.
  VectorType base(V), probed(V), direction(V), perturbed(V), brute(V);
  residual.evaluate(V, base, true);
  brute = 1.;
  for (unsigned int k = 0; k < V.size(); ++k)
    {
      if (!residual.is_active(k / 2))
        continue;
      direction                  = 0.;
      direction.local_element(k) = 1.;
      const double eps           = step(V, direction);
      perturbed                  = V;
      perturbed.add(eps, direction);
      residual.evaluate(perturbed, probed, true);
      brute.local_element(k) =
        (probed.local_element(k) - base.local_element(k)) / eps;
    }
  const double difference = max_relative_difference(diagonal, brute);
  deallog << "coloured = one-by-one diagonal with contact "
             "(max relative difference < 1e-6): "
          << (difference < 1e-6 ? "yes" : "no") << std::endl;
  if (difference >= 1e-6)
    deallog << "  max relative difference = " << difference << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  for (const std::string kernel : {"linear", "uGIMP"})
    for (const std::string mass_matrix : {"lumped", "blended"})
      {
        check_analytic_diagonal(kernel, mass_matrix);
        check_contact_diagonal(kernel, mass_matrix);
      }
}
