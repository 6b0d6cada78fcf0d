// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_particle_update_check_h
#define grainmpm_transfer_particle_update_check_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/transfer/transfer_options.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <cmath>
#include <limits>
#include <string>

namespace grainmpm
{
  /**
   * The checks of the grid-to-particle update of one material point of a
   * deformable grain (Transfer::grid_to_particles()): a value that is not
   * finite or, with TransferOptions::limit_move_to_one_cell, a move of more
   * than a cell in one step (check()), and a point that leaves the box
   * (leave_box()). Each gives the message of the InputError that names the
   * cause. (The points of rigid grains are checked by RigidGrainMotion.)
   */
  template <int dim>
  class ParticleUpdateCheck
  {
  public:
    /**
     * The checks for the run of @p parameters on @p grid, as @p options
     * ask.
     */
    ParticleUpdateCheck(const Parameters<dim>     &parameters,
                        const BackgroundGrid<dim> &grid,
                        const TransferOptions     &options);

    /**
     * What is wrong with the update of the material point @p id of the
     * deformable grain @p grain from @p old_position to @p new_position and
     * @p new_velocity in the step from @p time by @p dt: a non-finite value
     * (a diverged solution), or a move of more than one cell (a blow-up)
     * if the options limit it. Empty if nothing.
     */
    std::string
    check(const types::particle_index id,
          const unsigned int          grain,
          const Point<dim>           &old_position,
          const Point<dim>           &new_position,
          const Tensor<1, dim>       &new_velocity,
          const double                time,
          const double                dt) const
    {
      // A cheap test first (NaN fails every comparison): a finite velocity
      // and a move of at most a cell are fine.
      const Tensor<1, dim> &h          = cell_size;
      bool                  suspicious = false;
      for (unsigned int d = 0; d < dim; ++d)
        suspicious =
          suspicious ||
          !(std::abs(new_velocity[d]) <= std::numeric_limits<double>::max()) ||
          !(std::abs(new_position[d] - old_position[d]) <= h[d]);
      if (!suspicious)
        return std::string();
      return diagnose(
        id, grain, old_position, new_position, new_velocity, time, dt);
    }

    /**
     * The material point @p id of grain @p grain (rigid if @p rigid) whose
     * @p new_position at @p time lies outside the box, face after face: a
     * deformable point that crossed a closed face by less than half a
     * cell is put back on the face (counted in @p n_held_at_walls); a point
     * that crossed an open face is to be removed (@p removed set); through
     * a closed face otherwise, the returned message of the InputError says
     * where it left. Empty if there is no error.
     */
    std::string
    leave_box(const types::particle_index id,
              const unsigned int          grain,
              const bool                  rigid,
              Point<dim>                 &new_position,
              const double                time,
              types::particle_index      &n_held_at_walls,
              bool                       &removed) const
    {
      // Inside the box (the common case): nothing to do.
      bool inside = true;
      for (unsigned int d = 0; d < dim; ++d)
        inside = inside && new_position[d] >= lower_corner[d] &&
                 new_position[d] <= upper_corner[d];
      removed = false;
      if (inside)
        return std::string();
      return outside_box(
        id, grain, rigid, new_position, time, n_held_at_walls, removed);
    }

  private:
    /** leave_box() for a point outside the box (or not finite). */
    std::string
    outside_box(const types::particle_index id,
                const unsigned int          grain,
                const bool                  rigid,
                Point<dim>                 &new_position,
                const double                time,
                types::particle_index      &n_held_at_walls,
                bool                       &removed) const;

    /** check() for a suspicious point: decides and writes the message. */
    std::string
    diagnose(const types::particle_index id,
             const unsigned int          grain,
             const Point<dim>           &old_position,
             const Point<dim>           &new_position,
             const Tensor<1, dim>       &new_velocity,
             const double                time,
             const double                dt) const;

    const Parameters<dim>     &parameters;
    const BackgroundGrid<dim> &grid;
    const TransferOptions     &options;
    /** The grid's cell size and box (fixed for a run). */
    const Tensor<1, dim> cell_size;
    const Point<dim>     lower_corner;
    const Point<dim>     upper_corner;
  };
} // namespace grainmpm

#endif
