// ---------------------------------------------------------------------
//
// This file is part of grainmpm.
//
// ---------------------------------------------------------------------

#include "plain_kernel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

namespace grainmpm
{
  namespace benchmarks
  {
    namespace
    {
      /**
       * Particle data, stored as a structure of arrays: one vector per
       * field, all of length n_particles.
       */
      struct ParticleData
      {
        std::vector<double> position_x;
        std::vector<double> position_y;
        std::vector<double> velocity_x;
        std::vector<double> velocity_y;
        std::vector<double> mass;
        std::vector<double> volume;

        // Cauchy stress (plane strain, so the zz component is also needed).
        std::vector<double> stress_xx;
        std::vector<double> stress_yy;
        std::vector<double> stress_xy;
        std::vector<double> stress_zz;

        // In-plane deformation gradient F.
        std::vector<double> deformation_xx;
        std::vector<double> deformation_xy;
        std::vector<double> deformation_yx;
        std::vector<double> deformation_yy;

        void
        resize(const std::size_t n_particles)
        {
          for (std::vector<double> *field : {&position_x,
                                             &position_y,
                                             &velocity_x,
                                             &velocity_y,
                                             &mass,
                                             &volume,
                                             &stress_xx,
                                             &stress_yy,
                                             &stress_xy,
                                             &stress_zz,
                                             &deformation_xx,
                                             &deformation_xy,
                                             &deformation_yx,
                                             &deformation_yy})
            field->resize(n_particles);
        }
      };



      /**
       * Nodal data on the (n_cells+1) x (n_cells+1) grid nodes, stored as
       * flat vectors indexed by node_y * (n_cells+1) + node_x.
       */
      struct GridData
      {
        std::vector<double> mass;
        std::vector<double> momentum_x;
        std::vector<double> momentum_y;
        std::vector<double> force_x;
        std::vector<double> force_y;

        // Nodal velocity after P2G (v_i) and after the grid update (v_i^L).
        std::vector<double> velocity_x;
        std::vector<double> velocity_y;
        std::vector<double> new_velocity_x;
        std::vector<double> new_velocity_y;

        void
        resize(const std::size_t n_nodes)
        {
          for (std::vector<double> *field : {&mass,
                                             &momentum_x,
                                             &momentum_y,
                                             &force_x,
                                             &force_y,
                                             &velocity_x,
                                             &velocity_y,
                                             &new_velocity_x,
                                             &new_velocity_y})
            field->resize(n_nodes);
        }
      };



      /**
       * Shape function values, gradients and the global node indices of the
       * four nodes of the cell containing a particle. The local node order
       * is (0,0), (1,0), (0,1), (1,1) in the cell's reference coordinates.
       */
      struct CellShapeData
      {
        std::size_t node_index[4];
        double      value[4];
        double      gradient_x[4];
        double      gradient_y[4];
      };



      /**
       * Locate the cell containing the point (@p position_x, @p position_y)
       * on a uniform grid of @p n_cells x @p n_cells cells of size
       * 1 / @p inverse_cell_size and evaluate the bilinear (tent) shape
       * functions and their gradients there.
       */
      inline CellShapeData
      evaluate_shape_functions(const double       position_x,
                               const double       position_y,
                               const double       inverse_cell_size,
                               const unsigned int n_cells)
      {
        const double scaled_x = position_x * inverse_cell_size;
        const double scaled_y = position_y * inverse_cell_size;

        // Cell index floor(x/h), clamped so that particles exactly on (or
        // numerically just beyond) the boundary still find a valid cell.
        const int max_cell_index = static_cast<int>(n_cells) - 1;
        const int cell_x =
          std::clamp(static_cast<int>(std::floor(scaled_x)), 0, max_cell_index);
        const int cell_y =
          std::clamp(static_cast<int>(std::floor(scaled_y)), 0, max_cell_index);

        // Local coordinates in [0,1] within the cell.
        const double local_x = scaled_x - cell_x;
        const double local_y = scaled_y - cell_y;

        const std::size_t n_nodes_per_row = n_cells + 1;
        const std::size_t first_node =
          static_cast<std::size_t>(cell_y) * n_nodes_per_row + cell_x;

        CellShapeData data;
        data.node_index[0] = first_node;
        data.node_index[1] = first_node + 1;
        data.node_index[2] = first_node + n_nodes_per_row;
        data.node_index[3] = first_node + n_nodes_per_row + 1;

        data.value[0] = (1. - local_x) * (1. - local_y);
        data.value[1] = local_x * (1. - local_y);
        data.value[2] = (1. - local_x) * local_y;
        data.value[3] = local_x * local_y;

        data.gradient_x[0] = -(1. - local_y) * inverse_cell_size;
        data.gradient_x[1] = (1. - local_y) * inverse_cell_size;
        data.gradient_x[2] = -local_y * inverse_cell_size;
        data.gradient_x[3] = local_y * inverse_cell_size;

        data.gradient_y[0] = -(1. - local_x) * inverse_cell_size;
        data.gradient_y[1] = -local_x * inverse_cell_size;
        data.gradient_y[2] = (1. - local_x) * inverse_cell_size;
        data.gradient_y[3] = local_x * inverse_cell_size;

        return data;
      }
    } // namespace



    PlainKernelResult
    run_plain_kernel(const unsigned int n_cells,
                     const unsigned int particles_per_cell_per_direction,
                     const unsigned int n_steps)
    {
      // ------------------------------------------------------------------
      // Material and discretisation parameters.
      // ------------------------------------------------------------------
      const double youngs_modulus = 1000.;
      const double poisson_ratio  = 0.3;
      const double density        = 1.;
      const double gravity_x      = 0.;
      const double gravity_y      = -1.;

      const double lambda = youngs_modulus * poisson_ratio /
                            ((1. + poisson_ratio) * (1. - 2. * poisson_ratio));
      const double mu         = youngs_modulus / (2. * (1. + poisson_ratio));
      const double wave_speed = std::sqrt((lambda + 2. * mu) / density);

      const double cell_size         = 1. / n_cells;
      const double inverse_cell_size = static_cast<double>(n_cells);
      const double time_step         = 0.1 * cell_size / wave_speed;

      const std::size_t n_nodes_per_row = n_cells + 1;
      const std::size_t n_nodes         = n_nodes_per_row * n_nodes_per_row;

      const double mass_tolerance = 1e-14;

      // ------------------------------------------------------------------
      // Particle setup: all cells lying entirely inside [0.25,0.75]^2, with
      // particles_per_cell_per_direction^2 particles per cell placed at the
      // centres of a regular sub-grid, stored in cell order (row-major in
      // the cell indices, then row-major within each cell).
      // ------------------------------------------------------------------
      const unsigned int first_block_cell =
        static_cast<unsigned int>(std::ceil(0.25 * n_cells));
      const unsigned int end_block_cell =
        static_cast<unsigned int>(std::floor(0.75 * n_cells));
      const unsigned int n_block_cells_per_direction =
        (end_block_cell > first_block_cell) ?
          end_block_cell - first_block_cell :
          0;

      const std::size_t n_particles_per_cell =
        static_cast<std::size_t>(particles_per_cell_per_direction) *
        particles_per_cell_per_direction;
      const std::size_t n_particles =
        static_cast<std::size_t>(n_block_cells_per_direction) *
        n_block_cells_per_direction * n_particles_per_cell;

      const double particle_spacing =
        cell_size / particles_per_cell_per_direction;
      const double particle_volume = particle_spacing * particle_spacing;
      const double particle_mass   = density * particle_volume;

      ParticleData particles;
      particles.resize(n_particles);

      std::size_t particle = 0;
      for (unsigned int cell_y = first_block_cell; cell_y < end_block_cell;
           ++cell_y)
        for (unsigned int cell_x = first_block_cell; cell_x < end_block_cell;
             ++cell_x)
          for (unsigned int sub_y = 0; sub_y < particles_per_cell_per_direction;
               ++sub_y)
            for (unsigned int sub_x = 0;
                 sub_x < particles_per_cell_per_direction;
                 ++sub_x, ++particle)
              {
                particles.position_x[particle] =
                  cell_x * cell_size + (sub_x + 0.5) * particle_spacing;
                particles.position_y[particle] =
                  cell_y * cell_size + (sub_y + 0.5) * particle_spacing;
                particles.velocity_x[particle]     = 0.1;
                particles.velocity_y[particle]     = 0.;
                particles.mass[particle]           = particle_mass;
                particles.volume[particle]         = particle_volume;
                particles.stress_xx[particle]      = 0.;
                particles.stress_yy[particle]      = 0.;
                particles.stress_xy[particle]      = 0.;
                particles.stress_zz[particle]      = 0.;
                particles.deformation_xx[particle] = 1.;
                particles.deformation_xy[particle] = 0.;
                particles.deformation_yx[particle] = 0.;
                particles.deformation_yy[particle] = 1.;
              }

      GridData grid;
      grid.resize(n_nodes);

      // ------------------------------------------------------------------
      // Time stepping.
      // ------------------------------------------------------------------
      const auto start_time = std::chrono::steady_clock::now();

      for (unsigned int step = 0; step < n_steps; ++step)
        {
          // 1. Zero the nodal arrays.
          std::fill(grid.mass.begin(), grid.mass.end(), 0.);
          std::fill(grid.momentum_x.begin(), grid.momentum_x.end(), 0.);
          std::fill(grid.momentum_y.begin(), grid.momentum_y.end(), 0.);
          std::fill(grid.force_x.begin(), grid.force_x.end(), 0.);
          std::fill(grid.force_y.begin(), grid.force_y.end(), 0.);

          // 2. Particle-to-grid transfer of mass and momentum.
          for (std::size_t p = 0; p < n_particles; ++p)
            {
              const CellShapeData shape =
                evaluate_shape_functions(particles.position_x[p],
                                         particles.position_y[p],
                                         inverse_cell_size,
                                         n_cells);

              const double mass       = particles.mass[p];
              const double momentum_x = mass * particles.velocity_x[p];
              const double momentum_y = mass * particles.velocity_y[p];

              for (unsigned int i = 0; i < 4; ++i)
                {
                  const std::size_t node = shape.node_index[i];
                  grid.mass[node] += mass * shape.value[i];
                  grid.momentum_x[node] += momentum_x * shape.value[i];
                  grid.momentum_y[node] += momentum_y * shape.value[i];
                }
            }

          // 3. Nodal velocities v_i = p_i / m_i.
          for (std::size_t node = 0; node < n_nodes; ++node)
            if (grid.mass[node] > mass_tolerance)
              {
                const double inverse_mass = 1. / grid.mass[node];
                grid.velocity_x[node] = grid.momentum_x[node] * inverse_mass;
                grid.velocity_y[node] = grid.momentum_y[node] * inverse_mass;
              }
            else
              {
                grid.velocity_x[node] = 0.;
                grid.velocity_y[node] = 0.;
              }

          // 4. + 5. Update-stress-first stress update at the particles,
          // followed (in the same particle loop, since both need the same
          // shape data) by the scatter of internal and gravity forces.
          for (std::size_t p = 0; p < n_particles; ++p)
            {
              const CellShapeData shape =
                evaluate_shape_functions(particles.position_x[p],
                                         particles.position_y[p],
                                         inverse_cell_size,
                                         n_cells);

              // Velocity gradient L = sum_i v_i (x) grad S_i.
              double velocity_gradient_xx = 0.;
              double velocity_gradient_xy = 0.;
              double velocity_gradient_yx = 0.;
              double velocity_gradient_yy = 0.;
              for (unsigned int i = 0; i < 4; ++i)
                {
                  const std::size_t node            = shape.node_index[i];
                  const double      node_velocity_x = grid.velocity_x[node];
                  const double      node_velocity_y = grid.velocity_y[node];
                  velocity_gradient_xx += node_velocity_x * shape.gradient_x[i];
                  velocity_gradient_xy += node_velocity_x * shape.gradient_y[i];
                  velocity_gradient_yx += node_velocity_y * shape.gradient_x[i];
                  velocity_gradient_yy += node_velocity_y * shape.gradient_y[i];
                }

              // Strain increment dt sym(L) and spin increment dt skew(L).
              // The spin tensor has the single independent entry
              // dW_xy = -dW_yx.
              const double strain_increment_xx =
                time_step * velocity_gradient_xx;
              const double strain_increment_yy =
                time_step * velocity_gradient_yy;
              const double strain_increment_xy =
                0.5 * time_step * (velocity_gradient_xy + velocity_gradient_yx);
              const double spin_increment_xy =
                0.5 * time_step * (velocity_gradient_xy - velocity_gradient_yx);
              const double volumetric_strain_increment =
                strain_increment_xx + strain_increment_yy;

              // Jaumann rotation sigma += dW sigma - sigma dW. For the
              // in-plane 2x2 block this evaluates to the expressions below;
              // sigma_zz is unaffected by an in-plane rotation.
              double stress_xx = particles.stress_xx[p];
              double stress_yy = particles.stress_yy[p];
              double stress_xy = particles.stress_xy[p];
              double stress_zz = particles.stress_zz[p];

              const double rotation_diagonal =
                2. * spin_increment_xy * stress_xy;
              const double rotation_off_diagonal =
                spin_increment_xy * (stress_yy - stress_xx);
              stress_xx += rotation_diagonal;
              stress_yy -= rotation_diagonal;
              stress_xy += rotation_off_diagonal;

              // Linear elastic increment, plane strain (d_eps_zz = 0).
              const double lambda_trace = lambda * volumetric_strain_increment;
              stress_xx += lambda_trace + 2. * mu * strain_increment_xx;
              stress_yy += lambda_trace + 2. * mu * strain_increment_yy;
              stress_xy += 2. * mu * strain_increment_xy;
              stress_zz += lambda_trace;

              particles.stress_xx[p] = stress_xx;
              particles.stress_yy[p] = stress_yy;
              particles.stress_xy[p] = stress_xy;
              particles.stress_zz[p] = stress_zz;

              // Volume update V *= 1 + tr(d_eps).
              const double volume =
                particles.volume[p] * (1. + volumetric_strain_increment);
              particles.volume[p] = volume;

              // Deformation gradient update F = (I + dt L) F.
              const double deformation_xx = particles.deformation_xx[p];
              const double deformation_xy = particles.deformation_xy[p];
              const double deformation_yx = particles.deformation_yx[p];
              const double deformation_yy = particles.deformation_yy[p];
              particles.deformation_xx[p] =
                deformation_xx +
                time_step * (velocity_gradient_xx * deformation_xx +
                             velocity_gradient_xy * deformation_yx);
              particles.deformation_xy[p] =
                deformation_xy +
                time_step * (velocity_gradient_xx * deformation_xy +
                             velocity_gradient_xy * deformation_yy);
              particles.deformation_yx[p] =
                deformation_yx +
                time_step * (velocity_gradient_yx * deformation_xx +
                             velocity_gradient_yy * deformation_yx);
              particles.deformation_yy[p] =
                deformation_yy +
                time_step * (velocity_gradient_yx * deformation_xy +
                             velocity_gradient_yy * deformation_yy);

              // Internal force f_i -= V sigma . grad S_i plus gravity
              // m g S_i.
              const double mass            = particles.mass[p];
              const double gravity_force_x = mass * gravity_x;
              const double gravity_force_y = mass * gravity_y;
              for (unsigned int i = 0; i < 4; ++i)
                {
                  const std::size_t node = shape.node_index[i];
                  grid.force_x[node] +=
                    gravity_force_x * shape.value[i] -
                    volume * (stress_xx * shape.gradient_x[i] +
                              stress_xy * shape.gradient_y[i]);
                  grid.force_y[node] +=
                    gravity_force_y * shape.value[i] -
                    volume * (stress_xy * shape.gradient_x[i] +
                              stress_yy * shape.gradient_y[i]);
                }
            }

          // 6. Grid update v_i^L = v_i + dt f_i / m_i.
          for (std::size_t node = 0; node < n_nodes; ++node)
            if (grid.mass[node] > mass_tolerance)
              {
                const double velocity_scale = time_step / grid.mass[node];
                grid.new_velocity_x[node] =
                  grid.velocity_x[node] + velocity_scale * grid.force_x[node];
                grid.new_velocity_y[node] =
                  grid.velocity_y[node] + velocity_scale * grid.force_y[node];
              }
            else
              {
                grid.new_velocity_x[node] = 0.;
                grid.new_velocity_y[node] = 0.;
              }

          // Free-slip walls: zero the normal velocity component on the
          // nodes of the left/right (x = 0, x = 1) and bottom/top (y = 0,
          // y = 1) boundaries of the unit square.
          for (std::size_t row = 0; row < n_nodes_per_row; ++row)
            {
              grid.new_velocity_x[row * n_nodes_per_row]           = 0.;
              grid.new_velocity_x[row * n_nodes_per_row + n_cells] = 0.;
              grid.new_velocity_y[row]                             = 0.;
              grid.new_velocity_y[n_cells * n_nodes_per_row + row] = 0.;
            }

          // 7. Grid-to-particle transfer: FLIP velocity update and position
          // update with the updated nodal velocities.
          for (std::size_t p = 0; p < n_particles; ++p)
            {
              const CellShapeData shape =
                evaluate_shape_functions(particles.position_x[p],
                                         particles.position_y[p],
                                         inverse_cell_size,
                                         n_cells);

              double velocity_change_x    = 0.;
              double velocity_change_y    = 0.;
              double advection_velocity_x = 0.;
              double advection_velocity_y = 0.;
              for (unsigned int i = 0; i < 4; ++i)
                {
                  const std::size_t node           = shape.node_index[i];
                  const double      value          = shape.value[i];
                  const double      new_velocity_x = grid.new_velocity_x[node];
                  const double      new_velocity_y = grid.new_velocity_y[node];
                  velocity_change_x +=
                    value * (new_velocity_x - grid.velocity_x[node]);
                  velocity_change_y +=
                    value * (new_velocity_y - grid.velocity_y[node]);
                  advection_velocity_x += value * new_velocity_x;
                  advection_velocity_y += value * new_velocity_y;
                }

              particles.velocity_x[p] += velocity_change_x;
              particles.velocity_y[p] += velocity_change_y;
              particles.position_x[p] += time_step * advection_velocity_x;
              particles.position_y[p] += time_step * advection_velocity_y;
            }
        }

      const auto end_time = std::chrono::steady_clock::now();

      // ------------------------------------------------------------------
      // Timing and checksum.
      // ------------------------------------------------------------------
      const double elapsed_ns =
        std::chrono::duration<double, std::nano>(end_time - start_time).count();
      const double n_particle_steps =
        static_cast<double>(n_particles) * static_cast<double>(n_steps);

      double checksum = 0.;
      for (std::size_t p = 0; p < n_particles; ++p)
        checksum += particles.velocity_x[p];

      PlainKernelResult result;
      result.ns_per_particle_step =
        (n_particle_steps > 0.) ? elapsed_ns / n_particle_steps : 0.;
      result.checksum    = checksum;
      result.n_particles = static_cast<unsigned long>(n_particles);
      return result;
    }
  } // namespace benchmarks
} // namespace grainmpm
