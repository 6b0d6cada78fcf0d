// ---------------------------------------------------------------------
//
// This file is part of grainmpm.
//
// ---------------------------------------------------------------------

#ifndef grainmpm_benchmarks_explicit_step_plain_kernel_h
#define grainmpm_benchmarks_explicit_step_plain_kernel_h

/**
 * @file
 * A dependency-free (C++17 standard library only) plain-array implementation
 * of a 2D explicit Material Point Method step (and of a 3D one). It serves as
 * the reference "same work in plain arrays" kernel against which the deal.II
 * based implementation of the explicit step is compared.
 */

namespace grainmpm
{
  namespace benchmarks
  {
    /**
     * The outcome of a run of the plain-array kernel.
     */
    struct PlainKernelResult
    {
      /**
       * Wall time per particle and per step in nanoseconds, measured with
       * std::chrono::steady_clock over all steps (setup excluded).
       */
      double ns_per_particle_step;

      /**
       * Sum of the particle x velocities at the end of the run. Its only
       * purpose is to make sure that the compiler cannot optimise the work
       * away, and to allow a sanity check that the run stayed finite.
       */
      double checksum;

      /**
       * Number of particles in the run.
       */
      unsigned long n_particles;
    };



    /**
     * Run @p n_steps explicit update-stress-first (USF) MPM steps with
     * bilinear (Q1) shape functions on a uniform grid of
     * @p n_cells x @p n_cells cells covering the unit square.
     *
     * The particles fill the block $[0.25,0.75]^2$ (more precisely: all grid
     * cells lying entirely inside this block) with
     * @p particles_per_cell_per_direction squared particles per cell in a
     * regular arrangement, stored in cell order. The material is linear
     * elastic (plane strain, E = 1000, nu = 0.3, rho = 1) with a Jaumann
     * stress rate, initial velocity (0.1, 0), zero initial stress, gravity
     * (0, -1), free-slip walls on the boundary of the unit square, and a time
     * step of 0.1 h / c with the P-wave speed c.
     */
    PlainKernelResult
    run_plain_kernel(const unsigned int n_cells,
                     const unsigned int particles_per_cell_per_direction,
                     const unsigned int n_steps);

    /**
     * The same in 3D (plain_kernel_3d.cc): trilinear shape functions on a
     * uniform grid of @p n_cells^3 cells covering the unit cube, the block
     * of the cells inside $[0.25,0.75]^3$ with
     * @p particles_per_cell_per_direction cubed particles per cell, linear
     * elastic with a Jaumann stress rate, initial velocity (0.1, 0, 0),
     * gravity (0, -1, 0), free-slip walls, time step 0.1 h / c.
     */
    PlainKernelResult
    run_plain_kernel_3d(const unsigned int n_cells,
                        const unsigned int particles_per_cell_per_direction,
                        const unsigned int n_steps);
  } // namespace benchmarks
} // namespace grainmpm

#endif
