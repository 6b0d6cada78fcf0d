// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The finite-difference Jacobian-vector product of the implicit residual
// (eq. 15) equals the exact action of the Jacobian M^-1 (M + theta^2 dt^2
// K) (doc/theory.md section 11) on random vectors, for an
// unstressed elastic grain without contact, with both differencing steps;
// K is assembled independently in the test, M is the lumped mass (the
// blended mass matrix is tested by tests/implicit/probed_diagonal_01 and
// tests/transfer/consistent_mass_01). Also: the residual is a pure
// function (two evaluations are bit-identical and leave the particles
// untouched).

#include <grainmpm/solvers/newton_krylov.h>

#include <cstdlib>

#include "../tests.h"

#include "../implicit_fixture.h"
#include "elastic_block.h"

using namespace grainmpm;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  ImplicitFixture<2> fixture(elastic_block_parameters(R"(
subsection Time stepping
  set Mass matrix = lumped
end
)"),
                             "jacobian_fd_01");
  auto              &stepper = *fixture.stepper;
  const double       dt      = fixture.parameters.time_stepping.time_step;
  const double       theta   = fixture.parameters.time_stepping.theta;
  auto &residual = stepper.prepare(*fixture.particle_handler, 0., dt);

  using VectorType   = LinearAlgebra::distributed::Vector<double>;
  const VectorType V = stepper.get_old_velocities();
  VectorType       r0(V), r1(V);
  residual.evaluate(V, r0);
  residual.evaluate(V, r1);
  r1 -= r0;
  deallog << "unknowns: " << V.size() << std::endl;
  deallog << "two residual evaluations bit-identical: "
          << (r1.linfty_norm() == 0. ? "yes" : "no") << std::endl;

  // The same slots as the stepper's, for the independent K.
  TransferCache<2>    cache;
  GrainFieldLayout<2> layout;
  cache.reinit(*fixture.grid, *fixture.particle_handler, {0});
  layout.reinit(cache, *fixture.grid);
  AssertDimension(layout.n_slots() * 2, V.size());
  const VectorType &masses = stepper.get_masses();

  for (const std::string step : {"Pernice-Walker", "Knoll-Keyes"})
    {
      NonlinearSolverParameters nonlinear = fixture.parameters.nonlinear_solver;
      nonlinear.differencing_text         = step;
      nonlinear.check();
      const NewtonKrylovSolver solver(nonlinear,
                                      fixture.parameters.linear_solver,
                                      36.69);
      unsigned long long       state = 2024;
      for (unsigned int trial = 0; trial < 3; ++trial)
        {
          VectorType z(V), jz, kz, exact(V);
          for (unsigned int k = 0; k < z.size(); ++k)
            z.local_element(k) =
              residual.is_active(k / 2) ? 2. * uniform_random(state) - 1. : 0.;
          solver.jacobian_vmult(residual, V, r0, z, jz);
          stiffness_action(*fixture.grid,
                           *fixture.particle_handler,
                           cache,
                           block_lambda,
                           block_mu,
                           z,
                           kz);
          for (unsigned int k = 0; k < z.size(); ++k)
            exact.local_element(k) =
              z.local_element(k) + theta * theta * dt * dt *
                                     kz.local_element(k) /
                                     masses.local_element(k / 2);
          // The stiffness part must matter: compare it with the identity.
          VectorType stiffness_part(exact);
          stiffness_part -= z;
          jz -= exact;
          const double error = jz.l2_norm() / exact.l2_norm();
          deallog << step << ", vector " << trial << ": |K part| / |z| > 0.1: "
                  << (stiffness_part.l2_norm() > 0.1 * z.l2_norm() ? "yes" :
                                                                     "no")
                  << ", relative difference < 1e-6: "
                  << (error < 1e-6 ? "yes" : "no") << std::endl;
          if (error >= 1e-6 || std::getenv("GRAINMPM_VERBOSE") != nullptr)
            deallog << "  relative difference = " << error << std::endl;
        }
    }
}
