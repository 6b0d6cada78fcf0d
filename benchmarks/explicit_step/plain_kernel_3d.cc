// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The 3D counterpart of plain_kernel.cc: the same explicit USF step in
// plain arrays, with trilinear shape functions on a uniform grid of the
// unit cube.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

#include "plain_kernel.h"

namespace grainmpm
{
  namespace benchmarks
  {
    namespace
    {
      /** Particle data as a structure of arrays, one vector per component. */
      struct Particles3d
      {
        std::array<std::vector<double>, 3> position, velocity;
        std::vector<double>                mass, volume;
        // Stress in Voigt order xx, yy, zz, xy, xz, yz.
        std::array<std::vector<double>, 6> stress;
        // Deformation gradient F, row-major.
        std::array<std::vector<double>, 9> deformation;

        void
        resize(const std::size_t n)
        {
          for (auto *group : {&position, &velocity})
            for (auto &field : *group)
              field.resize(n);
          mass.resize(n);
          volume.resize(n);
          for (auto &field : stress)
            field.resize(n);
          for (auto &field : deformation)
            field.resize(n);
        }
      };



      /** Nodal data, indexed by (k (n + 1) + j) (n + 1) + i. */
      struct Grid3d
      {
        std::vector<double>                mass;
        std::array<std::vector<double>, 3> momentum, force, velocity,
          new_velocity;

        void
        resize(const std::size_t n)
        {
          mass.resize(n);
          for (auto *group : {&momentum, &force, &velocity, &new_velocity})
            for (auto &field : *group)
              field.resize(n);
        }
      };



      /** Values, gradients and node indices of the 8 nodes of a cell. */
      struct CellShapeData3d
      {
        std::size_t node_index[8];
        double      value[8];
        double      gradient[3][8];
      };



      inline CellShapeData3d
      evaluate_shape_functions_3d(const double       x,
                                  const double       y,
                                  const double       z,
                                  const double       inverse_cell_size,
                                  const unsigned int n_cells)
      {
        const double scaled[3] = {x * inverse_cell_size,
                                  y * inverse_cell_size,
                                  z * inverse_cell_size};
        const int    last      = static_cast<int>(n_cells) - 1;
        int          cell[3];
        double       local[3];
        for (unsigned int d = 0; d < 3; ++d)
          {
            cell[d] =
              std::clamp(static_cast<int>(std::floor(scaled[d])), 0, last);
            local[d] = scaled[d] - cell[d];
          }
        const std::size_t row   = n_cells + 1;
        const std::size_t plane = row * row;
        const std::size_t first =
          (static_cast<std::size_t>(cell[2]) * row + cell[1]) * row + cell[0];

        CellShapeData3d data;
        for (unsigned int v = 0; v < 8; ++v)
          {
            const unsigned int bit[3] = {v & 1U, (v >> 1) & 1U, (v >> 2) & 1U};
            data.node_index[v] = first + bit[0] + bit[1] * row + bit[2] * plane;
            double factor[3], derivative[3];
            for (unsigned int d = 0; d < 3; ++d)
              {
                factor[d]     = bit[d] ? local[d] : 1. - local[d];
                derivative[d] = bit[d] ? inverse_cell_size : -inverse_cell_size;
              }
            data.value[v]       = factor[0] * factor[1] * factor[2];
            data.gradient[0][v] = derivative[0] * factor[1] * factor[2];
            data.gradient[1][v] = factor[0] * derivative[1] * factor[2];
            data.gradient[2][v] = factor[0] * factor[1] * derivative[2];
          }
        return data;
      }
    } // namespace



    PlainKernelResult
    run_plain_kernel_3d(const unsigned int n_cells,
                        const unsigned int particles_per_cell_per_direction,
                        const unsigned int n_steps)
    {
      const double youngs_modulus = 1000., poisson_ratio = 0.3, density = 1.;
      const double gravity[3] = {0., -1., 0.};
      const double lambda     = youngs_modulus * poisson_ratio /
                            ((1. + poisson_ratio) * (1. - 2. * poisson_ratio));
      const double      mu = youngs_modulus / (2. * (1. + poisson_ratio));
      const double      wave_speed = std::sqrt((lambda + 2. * mu) / density);
      const double      cell_size  = 1. / n_cells;
      const double      inverse_cell_size = static_cast<double>(n_cells);
      const double      time_step         = 0.1 * cell_size / wave_speed;
      const std::size_t row               = n_cells + 1;
      const std::size_t n_nodes           = row * row * row;
      const double      mass_tolerance    = 1e-14;

      // The cells inside [0.25, 0.75]^3, ppc^3 points per cell at the
      // centres of a regular sub-grid, in cell order.
      const unsigned int first =
        static_cast<unsigned int>(std::ceil(0.25 * n_cells));
      const unsigned int end =
        static_cast<unsigned int>(std::floor(0.75 * n_cells));
      const unsigned int ppc             = particles_per_cell_per_direction;
      const double       spacing         = cell_size / ppc;
      const double       particle_volume = spacing * spacing * spacing;
      Particles3d        particles;
      std::size_t        n_particles = 0;
      if (end > first)
        n_particles = std::size_t(end - first) * (end - first) * (end - first) *
                      ppc * ppc * ppc;
      particles.resize(n_particles);
      std::size_t p = 0;
      for (unsigned int ck = first; ck < end; ++ck)
        for (unsigned int cj = first; cj < end; ++cj)
          for (unsigned int ci = first; ci < end; ++ci)
            for (unsigned int sk = 0; sk < ppc; ++sk)
              for (unsigned int sj = 0; sj < ppc; ++sj)
                for (unsigned int si = 0; si < ppc; ++si, ++p)
                  {
                    particles.position[0][p] =
                      ci * cell_size + (si + 0.5) * spacing;
                    particles.position[1][p] =
                      cj * cell_size + (sj + 0.5) * spacing;
                    particles.position[2][p] =
                      ck * cell_size + (sk + 0.5) * spacing;
                    particles.velocity[0][p] = 0.1;
                    particles.velocity[1][p] = 0.;
                    particles.velocity[2][p] = 0.;
                    particles.mass[p]        = density * particle_volume;
                    particles.volume[p]      = particle_volume;
                    for (auto &s : particles.stress)
                      s[p] = 0.;
                    for (unsigned int a = 0; a < 9; ++a)
                      particles.deformation[a][p] = (a % 4 == 0 ? 1. : 0.);
                  }

      Grid3d grid;
      grid.resize(n_nodes);
      const auto start_time = std::chrono::steady_clock::now();
      for (unsigned int step = 0; step < n_steps; ++step)
        {
          // 1. Zero the nodal arrays.
          std::fill(grid.mass.begin(), grid.mass.end(), 0.);
          for (unsigned int d = 0; d < 3; ++d)
            {
              std::fill(grid.momentum[d].begin(), grid.momentum[d].end(), 0.);
              std::fill(grid.force[d].begin(), grid.force[d].end(), 0.);
            }

          // 2. Particle-to-grid transfer of mass and momentum.
          for (std::size_t q = 0; q < n_particles; ++q)
            {
              const CellShapeData3d shape =
                evaluate_shape_functions_3d(particles.position[0][q],
                                            particles.position[1][q],
                                            particles.position[2][q],
                                            inverse_cell_size,
                                            n_cells);
              const double m = particles.mass[q];
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const std::size_t node = shape.node_index[v];
                  const double      w    = m * shape.value[v];
                  grid.mass[node] += w;
                  for (unsigned int d = 0; d < 3; ++d)
                    grid.momentum[d][node] += w * particles.velocity[d][q];
                }
            }

          // 3. Nodal velocities.
          for (std::size_t node = 0; node < n_nodes; ++node)
            {
              const double inverse_mass =
                grid.mass[node] > mass_tolerance ? 1. / grid.mass[node] : 0.;
              for (unsigned int d = 0; d < 3; ++d)
                grid.velocity[d][node] = grid.momentum[d][node] * inverse_mass;
            }

          // 4. + 5. USF stress update and the force scatter.
          for (std::size_t q = 0; q < n_particles; ++q)
            {
              const CellShapeData3d shape =
                evaluate_shape_functions_3d(particles.position[0][q],
                                            particles.position[1][q],
                                            particles.position[2][q],
                                            inverse_cell_size,
                                            n_cells);
              // L_ab = sum_v v_a grad_b S_v.
              double L[3][3] = {};
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const std::size_t node = shape.node_index[v];
                  for (unsigned int a = 0; a < 3; ++a)
                    for (unsigned int b = 0; b < 3; ++b)
                      L[a][b] += grid.velocity[a][node] * shape.gradient[b][v];
                }
              double strain[3][3], spin[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  {
                    strain[a][b] = 0.5 * time_step * (L[a][b] + L[b][a]);
                    spin[a][b]   = 0.5 * time_step * (L[a][b] - L[b][a]);
                  }
              const double trace = strain[0][0] + strain[1][1] + strain[2][2];

              // The stress as a full matrix, Jaumann rotation and the
              // elastic increment.
              const unsigned int voigt[3][3] = {{0, 3, 4},
                                                {3, 1, 5},
                                                {4, 5, 2}};
              double             s[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  s[a][b] = particles.stress[voigt[a][b]][q];
              double updated[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  {
                    double r = s[a][b];
                    for (unsigned int c = 0; c < 3; ++c)
                      r += spin[a][c] * s[c][b] - s[a][c] * spin[c][b];
                    updated[a][b] = r + 2. * mu * strain[a][b] +
                                    (a == b ? lambda * trace : 0.);
                  }
              particles.stress[0][q] = updated[0][0];
              particles.stress[1][q] = updated[1][1];
              particles.stress[2][q] = updated[2][2];
              particles.stress[3][q] = updated[0][1];
              particles.stress[4][q] = updated[0][2];
              particles.stress[5][q] = updated[1][2];

              const double volume = particles.volume[q] * (1. + trace);
              particles.volume[q] = volume;

              // F = (I + dt L) F.
              double F[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  F[a][b] = particles.deformation[3 * a + b][q];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  {
                    double increment = 0.;
                    for (unsigned int c = 0; c < 3; ++c)
                      increment += L[a][c] * F[c][b];
                    particles.deformation[3 * a + b][q] =
                      F[a][b] + time_step * increment;
                  }

              // f_v += m g S_v - V sigma grad S_v.
              const double m = particles.mass[q];
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const std::size_t node = shape.node_index[v];
                  for (unsigned int a = 0; a < 3; ++a)
                    grid.force[a][node] +=
                      m * gravity[a] * shape.value[v] -
                      volume * (updated[a][0] * shape.gradient[0][v] +
                                updated[a][1] * shape.gradient[1][v] +
                                updated[a][2] * shape.gradient[2][v]);
                }
            }

          // 6. Grid update, then free-slip walls on the six faces.
          for (std::size_t node = 0; node < n_nodes; ++node)
            {
              const double scale = grid.mass[node] > mass_tolerance ?
                                     time_step / grid.mass[node] :
                                     0.;
              for (unsigned int d = 0; d < 3; ++d)
                grid.new_velocity[d][node] =
                  grid.mass[node] > mass_tolerance ?
                    grid.velocity[d][node] + scale * grid.force[d][node] :
                    0.;
            }
          for (std::size_t a = 0; a < row; ++a)
            for (std::size_t b = 0; b < row; ++b)
              {
                grid.new_velocity[0][(a * row + b) * row]           = 0.;
                grid.new_velocity[0][(a * row + b) * row + n_cells] = 0.;
                grid.new_velocity[1][(a * row) * row + b]           = 0.;
                grid.new_velocity[1][(a * row + n_cells) * row + b] = 0.;
                grid.new_velocity[2][a * row + b]                   = 0.;
                grid.new_velocity[2][(n_cells * row + a) * row + b] = 0.;
              }

          // 7. FLIP velocity update and position update.
          for (std::size_t q = 0; q < n_particles; ++q)
            {
              const CellShapeData3d shape =
                evaluate_shape_functions_3d(particles.position[0][q],
                                            particles.position[1][q],
                                            particles.position[2][q],
                                            inverse_cell_size,
                                            n_cells);
              double change[3] = {}, advection[3] = {};
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const std::size_t node = shape.node_index[v];
                  for (unsigned int d = 0; d < 3; ++d)
                    {
                      const double new_velocity = grid.new_velocity[d][node];
                      change[d] += shape.value[v] *
                                   (new_velocity - grid.velocity[d][node]);
                      advection[d] += shape.value[v] * new_velocity;
                    }
                }
              for (unsigned int d = 0; d < 3; ++d)
                {
                  particles.velocity[d][q] += change[d];
                  particles.position[d][q] += time_step * advection[d];
                }
            }
        }
      const auto end_time = std::chrono::steady_clock::now();

      const double elapsed_ns =
        std::chrono::duration<double, std::nano>(end_time - start_time).count();
      double checksum = 0.;
      for (std::size_t q = 0; q < n_particles; ++q)
        checksum += particles.velocity[0][q];
      PlainKernelResult result;
      result.ns_per_particle_step =
        n_particles * n_steps > 0 ?
          elapsed_ns / (static_cast<double>(n_particles) * n_steps) :
          0.;
      result.checksum    = checksum;
      result.n_particles = static_cast<unsigned long>(n_particles);
      return result;
    }
  } // namespace benchmarks
} // namespace grainmpm
