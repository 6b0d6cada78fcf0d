// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_transfer_cache_h
#define grainmpm_transfer_transfer_cache_h

#include <grainmpm/base/config.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace grainmpm
{
  /**
   * Call @p action(cell, particle) for every locally owned particle, cell by
   * cell. This is the order of the TransferCache arrays: every loop that
   * uses the cache visits the particles through this function.
   */
  template <int dim, typename ParticleHandlerType, typename Action>
  void
  for_each_particle(const BackgroundGrid<dim> &grid,
                    ParticleHandlerType       &particle_handler,
                    Action                   &&action)
  {
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          auto particles = particle_handler.particles_in_cell(cell);
          for (auto particle = particles.begin(); particle != particles.end();
               ++particle)
            action(cell, particle);
        }
  }



  /**
   * Everything the particle-grid transfers of one step need that depends
   * only on the particle positions at the start of the step, in flat
   * arrays in the order in which `for (auto &particle : particle_handler)`
   * visits the particles (see doc/theory.md): for each particle its
   * 2^dim nodes, the Q1 shape values S_ip and gradients grad S_ip
   * evaluated directly from the reference location (the cells are
   * axis-aligned boxes), and its velocity field (the grain, or the common
   * field when grains do not have their own fields). The slot of each
   * (particle, node) pair is filled in by GrainFieldLayout::reinit().
   */
  template <int dim>
  class TransferCache
  {
  public:
    static constexpr unsigned int nodes_per_particle = 1U << dim;

    /**
     * Compute the cache for the particles of @p particle_handler on
     * @p grid. @p field_of_grain maps a grain to its velocity field.
     */
    void
    reinit(const BackgroundGrid<dim>             &grid,
           const Particles::ParticleHandler<dim> &particle_handler,
           const std::vector<unsigned int>       &field_of_grain);

    /** Number of particles. */
    std::size_t
    n_particles() const
    {
      return fields.size();
    }

    /** Node of local vertex @p v of particle @p p. */
    std::vector<unsigned int> nodes;
    /** S_ip for the same pairs. */
    std::vector<double> shape_values;
    /** grad S_ip for the same pairs. */
    std::vector<Tensor<1, dim>> shape_gradients;
    /** Velocity field of each particle. */
    std::vector<unsigned int> fields;
    /** Slot of each (particle, vertex) pair; set by GrainFieldLayout. */
    std::vector<unsigned int> slots;
  };
} // namespace grainmpm

#endif
