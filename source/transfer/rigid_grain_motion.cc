// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/transfer/rigid_grain_motion.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    /** Whether every component of @p value is finite. */
    template <int dim, typename Value>
    bool
    is_finite(const Value &value)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (!std::isfinite(value[d]))
          return false;
      return true;
    }
  } // namespace



  template <int dim>
  RigidGrainMotion<dim>::RigidGrainMotion(
    const std::vector<GrainInfo<dim>>       &grains,
    const std::vector<GrainParameters<dim>> &grain_parameters,
    const BackgroundGrid<dim>               &grid)
    : grains(grains)
    , grain_parameters(grain_parameters)
    , grid(grid)
    , has_rigid_grains(
        std::any_of(grains.begin(), grains.end(), [](const auto &grain) {
          return grain.rigid;
        }))
  {}



  template <int dim>
  Tensor<1, dim>
  RigidGrainMotion<dim>::velocity(const GrainInfo<dim> &grain,
                                  const Point<dim>     &point,
                                  const double          time)
  {
    Vector<double>       value(dim);
    FunctionParser<dim> &function = *grain.prescribed_velocity;
    function.set_time(time);
    function.vector_value(point, value);
    Tensor<1, dim> velocity;
    for (unsigned int d = 0; d < dim; ++d)
      velocity[d] = value[d];
    return velocity;
  }



  template <int dim>
  Point<dim>
  RigidGrainMotion<dim>::move(const GrainInfo<dim> &grain,
                              const Point<dim>     &point,
                              const double          midpoint_time,
                              const double          dt)
  {
    const Tensor<1, dim> midpoint_velocity =
      velocity(grain, point, midpoint_time);
    Point<dim> moved;
    for (unsigned int d = 0; d < dim; ++d)
      moved[d] = point[d] + dt * midpoint_velocity[d];
    return moved;
  }



  template <int dim>
  void
  RigidGrainMotion<dim>::prescribe(const GrainFieldLayout<dim> &layout,
                                   VectorType                  &velocities,
                                   const double                 time) const
  {
    if (!has_rigid_grains)
      return;
    std::string error;
    for (unsigned int slot = 0; slot < layout.n_slots(); ++slot)
      {
        const unsigned int field = layout.field(slot);
        if (!grains[field].rigid)
          continue;
        const Point<dim>    &node  = grid.node_position(layout.node(slot));
        const Tensor<1, dim> value = velocity(grains[field], node, time);
        for (unsigned int d = 0; d < dim; ++d)
          velocities.local_element(slot * dim + d) = value[d];
        if (error.empty() && !is_finite<dim>(value))
          error = not_finite(field, time, 0., "a grid node", node);
      }
    throw_on_all_ranks(error, grid.get_triangulation().get_communicator());
  }



  template <int dim>
  std::string
  RigidGrainMotion<dim>::move_point(const unsigned int          grain,
                                    const types::particle_index id,
                                    const Point<dim>           &old_position,
                                    const double                time,
                                    const double                dt,
                                    Point<dim>                 &new_position,
                                    Tensor<1, dim> &new_velocity) const
  {
    new_position = move(grains[grain], old_position, time + 0.5 * dt, dt);
    new_velocity = velocity(grains[grain], new_position, time + dt);
    if (is_finite<dim>(new_velocity) && is_finite<dim>(new_position))
      return "";
    return not_finite(grain,
                      time + dt,
                      dt,
                      "the material point " + std::to_string(id),
                      old_position);
  }



  template <int dim>
  std::string
  RigidGrainMotion<dim>::not_finite(const unsigned int grain,
                                    const double       time,
                                    const double       dt,
                                    const std::string &where,
                                    const Point<dim>  &position) const
  {
    std::ostringstream message;
    message << "at t = " << time;
    if (dt > 0.)
      message << " (step dt = " << dt << ")";
    message << " it is not finite at " << where << " of the rigid grain "
            << grain + 1 << " at x = (" << position
            << "): the velocity must be finite at all times.";
    const GrainParameters<dim> &source = grain_parameters[grain];
    return InputError(source.source +
                        "/Prescribed velocity = " + source.prescribed_velocity,
                      message.str())
      .what();
  }



  template class RigidGrainMotion<2>;
  template class RigidGrainMotion<3>;
} // namespace grainmpm
