// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/transfer/particle_update_check.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    const char *const boundary_type_names[4] = {"free slip",
                                                "no slip",
                                                "friction",
                                                "open"};
  } // namespace



  template <int dim>
  ParticleUpdateCheck<dim>::ParticleUpdateCheck(
    const Parameters<dim>     &parameters,
    const BackgroundGrid<dim> &grid,
    const TransferOptions     &options)
    : parameters(parameters)
    , grid(grid)
    , options(options)
    , cell_size(grid.cell_size())
    , lower_corner(grid.lower_corner())
    , upper_corner(grid.upper_corner())
  {}



  template <int dim>
  std::string
  ParticleUpdateCheck<dim>::diagnose(const types::particle_index id,
                                     const unsigned int          grain,
                                     const Point<dim>           &old_position,
                                     const Point<dim>           &new_position,
                                     const Tensor<1, dim>       &new_velocity,
                                     const double                time,
                                     const double                dt) const
  {
    bool   finite        = true;
    double cells_crossed = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      {
        finite = finite && std::isfinite(new_velocity[d]) &&
                 std::isfinite(new_position[d]);
        cells_crossed = std::max(cells_crossed,
                                 std::abs(new_position[d] - old_position[d]) /
                                   grid.cell_size()[d]);
      }
    if (finite && (!options.limit_move_to_one_cell || !(cells_crossed > 1.)))
      return "";

    std::ostringstream message;
    message << "at t = " << time + dt << " (step dt = " << dt << ") ";
    message << "material point " << id << " of grain " << grain + 1 << " ("
            << parameters.grains[grain].source << ") ";
    if (!finite)
      message << "got a non-finite velocity or position: the solution "
                 "diverged. ";
    else
      message << "moved " << cells_crossed
              << " cells in one step, faster than the explicit step can "
                 "follow: the solution is blowing up. ";
    message << options.divergence_advice;
    std::ostringstream entry;
    if (parameters.time_stepping.time_step > 0.)
      entry << "Time stepping/Time step = "
            << parameters.time_stepping.time_step;
    else
      entry << "Time stepping/CFL number = "
            << parameters.time_stepping.cfl_number;
    return InputError(entry.str(), message.str()).what();
  }



  template <int dim>
  std::string
  ParticleUpdateCheck<dim>::outside_box(const types::particle_index id,
                                        const unsigned int          grain,
                                        const bool                  rigid,
                                        Point<dim>            &new_position,
                                        const double           time,
                                        types::particle_index &n_held_at_walls,
                                        bool                  &removed) const
  {
    const Tensor<1, dim> &h     = cell_size;
    const Point<dim>     &lower = lower_corner;
    const Point<dim>     &upper = upper_corner;
    removed                     = false;
    for (unsigned int d = 0; d < dim; ++d)
      if (new_position[d] < lower[d] || new_position[d] > upper[d])
        {
          const unsigned int face =
            2 * d + (new_position[d] > upper[d] ? 1 : 0);
          const BoundaryCondition &condition = grid.boundary_condition(face);
          const double             overshoot =
            std::max(lower[d] - new_position[d], new_position[d] - upper[d]);
          if (condition.type != BoundaryType::open && !rigid &&
              overshoot < 0.5 * h[d])
            {
              new_position[d] = (face % 2 == 0) ? lower[d] : upper[d];
              ++n_held_at_walls;
              continue;
            }
          if (condition.type == BoundaryType::open)
            {
              removed = true;
              return "";
            }
          std::ostringstream message;
          message << "particle " << id << " of grain " << grain + 1 << " ("
                  << parameters.grains[grain].source
                  << ") left the background grid through the closed face "
                  << face_name(face) << " ("
                  << boundary_type_names[static_cast<int>(condition.type)]
                  << ") at position (";
          for (unsigned int e = 0; e < dim; ++e)
            message << (e > 0 ? ", " : "") << new_position[e];
          message << ") at time " << time
                  << ". Enlarge the grid (Background grid/Lower corner, "
                     "Upper corner) or make that face open (Background "
                     "grid/Boundary conditions).";
          return message.str();
        }
    return "";
  }



  template class ParticleUpdateCheck<2>;
  template class ParticleUpdateCheck<3>;
} // namespace grainmpm
