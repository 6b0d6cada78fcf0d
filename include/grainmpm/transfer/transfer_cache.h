// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_transfer_cache_h
#define grainmpm_transfer_transfer_cache_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/signals2/connection.hpp>

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
   * only on the particle positions (and, for cpGIMP, deformations) at the
   * start of the step, in flat arrays in the order in which
   * for_each_particle() visits the particles: for each particle the list of
   * its (node, weight) entries, entries first_entry[p] to
   * first_entry[p + 1] - 1, with the node, the shape value S_ip and its
   * gradient grad S_ip, and the particle's velocity field (the grain, or
   * the common field when grains do not have their own fields). The slot
   * of each entry is filled in by GrainFieldLayout::reinit().
   *
   * The weights (see doc/theory.md):
   * - linear: the Q1 hats of the 2^dim vertices of the particle's cell,
   *   evaluated directly from the reference location (the cells are
   *   axis-aligned boxes);
   * - uGIMP and cpGIMP: per axis the hat N averaged over the particle's
   *   interval [x - l, x + l] cut at the box faces,
   *   S = (Phi(b) - Phi(a)) / (b - a) and dS/dx = (N(b) - N(a)) / (b - a)
   *   with Phi the integral of N, multiplied over the axes. With l at most
   *   half a cell a particle touches 2 or 3 nodes per axis; only the nodes
   *   with a positive weight are listed.
   */
  template <int dim>
  class TransferCache
  {
  public:
    /** The most entries a particle can have (3 nodes per axis). */
    static constexpr unsigned int max_nodes_per_particle = dim == 2 ? 9 : 27;

    /**
     * Compute the cache for the particles of @p particle_handler on
     * @p grid with the weights @p shape_functions. @p field_of_grain maps a
     * grain to its velocity field. @p half_width is the half-width l of a
     * particle's box in each direction at F = I (GIMP only; at most half a
     * cell). A particle at the same place in the order as at the last
     * reinit() (the same id there) keeps its field: its grain is read from
     * its properties only when it is new there, which saves a pass over
     * all point data while the points keep their cells.
     */
    void
    reinit(const BackgroundGrid<dim>             &grid,
           const Particles::ParticleHandler<dim> &particle_handler,
           const std::vector<unsigned int>       &field_of_grain,
           const ShapeFunctions  shape_functions = ShapeFunctions::linear,
           const Tensor<1, dim> &half_width      = Tensor<1, dim>());

    /**
     * Call @p action(cell, particle) for every locally owned particle in
     * the order of grainmpm::for_each_particle(), visiting only the cells
     * that held particles at the last reinit() (found there without a loop
     * over all cells while no particle entered an empty cell and the
     * triangulation did not change).
     */
    template <typename ParticleHandlerType, typename Action>
    void
    for_each_particle(ParticleHandlerType &particle_handler,
                      Action             &&action) const
    {
      for (const auto &cell : cells)
        {
          auto particles = particle_handler.particles_in_cell(cell);
          for (auto particle = particles.begin(); particle != particles.end();
               ++particle)
            action(cell, particle);
        }
    }

    /**
     * Whether the last reinit() changed the entries' nodes, the particles'
     * first entries or their fields, found the cells again (at first and
     * after a change of the triangulation), or saw another number of
     * particles: the slots of GrainFieldLayout, a function of these, are
     * kept while no rank's entries changed.
     */
    bool
    entries_changed() const
    {
      return changed;
    }

    /** Number of particles. */
    std::size_t
    n_particles() const
    {
      return fields.size();
    }

    /** Number of entries of all particles. */
    unsigned int
    n_entries() const
    {
      return first_entry.empty() ? 0 : first_entry.back();
    }

    /**
     * Call @p action(e) for the entries e of particle @p p. With linear
     * shape functions every particle has 2^dim entries, and the loop has
     * that fixed length (unrolled by the compiler: the particle loops then
     * cost 13 % fewer instructions than with the general bounds).
     */
    template <typename Action>
    void
    for_each_entry(const std::size_t p, Action &&action) const
    {
      if (shape_functions == ShapeFunctions::linear)
        {
          constexpr unsigned int n     = 1U << dim;
          const unsigned int     first = p * n;
          for (unsigned int v = 0; v < n; ++v)
            action(first + v);
        }
      else
        {
          const unsigned int end = first_entry[p + 1];
          for (unsigned int e = first_entry[p]; e < end; ++e)
            action(e);
        }
    }

    /** First entry of each particle; first_entry[n_particles()] ends. */
    std::vector<unsigned int> first_entry;
    /**
     * Node of each entry. This and the arrays below may be longer than
     * n_entries(): the entries beyond are unused.
     */
    std::vector<unsigned int> nodes;
    /** S_ip of each entry. */
    std::vector<double> shape_values;
    /** grad S_ip of each entry. */
    std::vector<Tensor<1, dim>> shape_gradients;
    /** Velocity field of each particle. */
    std::vector<unsigned int> fields;
    /** Id of each particle (whose field is in #fields). */
    std::vector<types::particle_index> ids;
    /** Slot of each entry; set by GrainFieldLayout. */
    std::vector<unsigned int> slots;

    /**
     * The locally owned active cells that hold particles, in active-cell
     * order.
     */
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;

  private:
    /**
     * Bring #cells up to date: keep them while every locally owned particle
     * is in one of them (a particle changes cells only when the particle
     * handler sorts, and a particle that entered a cell not in the list is
     * missing from the count) and the triangulation has not changed since;
     * else loop over all cells. Returns whether the cells were found again.
     */
    bool
    update_cells(const BackgroundGrid<dim>             &grid,
                 const Particles::ParticleHandler<dim> &particle_handler);

    /**
     * Fill the entries of every particle for Q1 shape functions (the
     * 2^dim vertices of its cell), and its field if @p read_all_fields or
     * its id differs from that at its place; returns the number of
     * entries.
     */
    unsigned int
    fill_linear(const BackgroundGrid<dim>             &grid,
                const Particles::ParticleHandler<dim> &particle_handler,
                const std::vector<unsigned int>       &field_of_grain,
                const bool                             read_all_fields);

    /**
     * Fill the entries of every particle for uGIMP or cpGIMP: per axis the
     * nodes with a positive weight for the particle's interval of
     * @p half_width (cpGIMP: stretched by F, at most half a cell), cut at
     * the box, and their tensor products, and the particle's field as in
     * fill_linear(). Returns the number of entries.
     */
    unsigned int
    fill_gimp(const BackgroundGrid<dim>             &grid,
              const Particles::ParticleHandler<dim> &particle_handler,
              const std::vector<unsigned int>       &field_of_grain,
              const Tensor<1, dim>                  &half_width,
              const bool                             read_all_fields);

    ShapeFunctions shape_functions = ShapeFunctions::linear;

    /** See entries_changed(). */
    bool changed = true;

    /**
     * False when #cells must be found again: at first, and after every
     * change of the triangulation (refinement, repartitioning, loading),
     * which invalidates its iterators.
     */
    bool cells_valid = false;

    /** The triangulation whose changes reset cells_valid. */
    const Triangulation<dim>          *watched_triangulation = nullptr;
    boost::signals2::scoped_connection triangulation_changed[3];
  };
} // namespace grainmpm

#endif
