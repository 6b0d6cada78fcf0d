// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Explicit-step benchmark (doc/validation.md, Performance): a block of
// elastic material filling [0.25, 0.75]^2 of a 512 x 512 grid with 4 x 4
// points per cell (1,048,576 material points), advanced by grainmpm's
// ExplicitLeapfrog, next to the plain-array kernel of the same work in the
// same process.
// Prints ns/particle/step of both and their ratio.
//
// Usage: explicit_step [n_cells=512] [particles_per_direction=4] [steps=10]
//                      [shape functions=linear]
// (the plain kernel always uses the linear hats). With "plain" or "plain3d"
// as the shape functions, only the 2D or the 3D plain-array kernel runs
// (on an n_cells^3 grid in 3D).

#include <grainmpm/time_integration/explicit_leapfrog.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <iostream>

#include "../common/elastic_block.h"
#include "plain_kernel.h"

using namespace grainmpm;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int n_cells = argc > 1 ? std::stoi(argv[1]) : 512;
  const unsigned int per_dir = argc > 2 ? std::stoi(argv[2]) : 4;
  const unsigned int n_steps = argc > 3 ? std::stoi(argv[3]) : 10;
  const std::string  kernel  = argc > 4 ? argv[4] : "linear";
  if (kernel == "plain")
    {
      // Only the plain-array kernel (benchmarks/whole_process.sh).
      const auto plain =
        benchmarks::run_plain_kernel(n_cells, per_dir, n_steps);
      std::cout << "  plain-array kernel:        " << plain.ns_per_particle_step
                << " ns/particle/step\n";
      return 0;
    }
  if (kernel == "plain3d")
    {
      // Only the 3D plain-array kernel (benchmarks/whole_process.sh, DIM=3).
      const auto plain =
        benchmarks::run_plain_kernel_3d(n_cells, per_dir, n_steps);
      std::cout << "  plain-array kernel:        " << plain.ns_per_particle_step
                << " ns/particle/step (3D, " << plain.n_particles
                << " particles, checksum " << plain.checksum << ")\n";
      return 0;
    }
  const double dt = 0.1 / n_cells / benchmarks::ElasticBlock::wave_speed();

  // The same block as the plain kernel: the cells inside [0.25, 0.75]^2.
  benchmarks::ElasticBlock block(
    n_cells,
    per_dir,
    "0.1; 0",
    dt,
    "subsection Physics\n  set Gravity = 0, -1\nend\n"
    "subsection Material points\n  set Shape functions = " +
      kernel + "\nend\n");
  auto               &particle_handler = *block.particle_handler;
  ExplicitLeapfrog<2> stepper(block.parameters,
                              *block.grid,
                              block.grains,
                              block.materials);

  block.move_off_arrangement();
  const double n_particles = particle_handler.n_global_particles();
  stepper.advance(particle_handler, 0., dt); // warm-up: allocations
  unsigned int n_sorted = 0;
  const auto   start    = std::chrono::steady_clock::now();
  for (unsigned int step = 1; step <= n_steps; ++step)
    n_sorted += stepper.advance(particle_handler, step * dt, dt).events.sorted;
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
  const double grainmpm_ns = 1e9 * seconds / (n_particles * n_steps);

  // Worst case: a particle changes cells in every step, so every step ends
  // with a full sort.
  const auto sort_start = std::chrono::steady_clock::now();
  for (unsigned int step = 0; step < n_steps; ++step)
    particle_handler.sort_particles_into_subdomains_and_cells();
  const double sort_ns =
    1e9 *
    std::chrono::duration<double>(std::chrono::steady_clock::now() - sort_start)
      .count() /
    (n_particles * n_steps);

  const auto plain = benchmarks::run_plain_kernel(n_cells, per_dir, n_steps);

  std::cout << "explicit step benchmark: " << n_cells << "^2 cells, " << kernel
            << " shape functions, " << static_cast<unsigned long>(n_particles)
            << " material points, " << n_steps << " steps (" << n_sorted
            << " with sorting)\n"
            << "  grainmpm ExplicitLeapfrog: " << grainmpm_ns
            << " ns/particle/step (" << 1e3 / grainmpm_ns
            << " M particle-updates/s)\n"
            << "  plain-array kernel:        " << plain.ns_per_particle_step
            << " ns/particle/step\n"
            << "  ratio:                     "
            << grainmpm_ns / plain.ns_per_particle_step << " (goal <= 3)\n"
            << "  one full sort:             " << sort_ns << " ns/particle\n"
            << "  ratio with a sort every step: "
            << (grainmpm_ns + sort_ns) / plain.ns_per_particle_step << "\n";
  return 0;
}
