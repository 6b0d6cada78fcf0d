// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/grain_geometry.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/rigid_grain_motion.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
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
        std::any_of(grains.begin(),
                    grains.end(),
                    [](const auto &grain) { return grain.rigid; }))
    , translated(grains.size())
    , displacements(grains.size())
  {
    for (unsigned int g = 0; g < grains.size(); ++g)
      translated[g] = grains[g].rigid;
  }



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
  void
  RigidGrainMotion<dim>::locate(
    const Particles::ParticleHandler<dim> &particle_handler,
    const double                           time,
    const double                           dt)
  {
    if (!has_rigid_grains)
      return;
    const double tolerance = 1e-12 * std::max(1., std::abs(time));
    if (std::abs(time - located_time) <= tolerance)
      {
        // The same step again (a rejected step is retried): the points
        // have not moved. (Before the first call the time is NaN, and
        // neither this nor the next test holds.)
        located_dt = dt;
        return;
      }
    if (std::abs(time - (located_time + located_dt)) <= tolerance)
      {
        // One step on: a uniform velocity moved every point, and so their
        // mean, by dt u(t + dt/2) (the midpoint rule of move()).
        const double midpoint = located_time + 0.5 * located_dt;
        for (unsigned int g = 0; g < grains.size(); ++g)
          if (translated[g])
            {
              translated[g] = uniform_velocity(g, displacements[g], midpoint) &&
                              uniform_velocity(g, displacements[g], time);
              displacements[g] +=
                located_dt * velocity(grains[g],
                                      grains[g].centroid + displacements[g],
                                      midpoint);
            }
      }
    else
      locate_from_points(particle_handler, time);
    located_time = time;
    located_dt   = dt;
  }



  template <int dim>
  void
  RigidGrainMotion<dim>::locate_from_points(
    const Particles::ParticleHandler<dim> &particle_handler,
    const double                           time)
  {
    // Per grain: the sum of the points' positions, then their number.
    std::vector<double> sums(grains.size() * (dim + 1), 0.);
    for (const auto &particle : particle_handler)
      {
        const unsigned int grain =
          MaterialPointLayout<dim>::get_grain(particle.get_properties());
        if (!translated[grain])
          continue;
        const Point<dim> &position = particle.get_location();
        for (unsigned int d = 0; d < dim; ++d)
          sums[grain * (dim + 1) + d] += position[d];
        sums[grain * (dim + 1) + dim] += 1.;
      }
    Utilities::MPI::sum(sums,
                        grid.get_triangulation().get_communicator(),
                        sums);
    for (unsigned int g = 0; g < grains.size(); ++g)
      {
        if (!translated[g])
          continue;
        const double n_points = sums[g * (dim + 1) + dim];
        if (n_points != static_cast<double>(grains[g].n_particles))
          {
            translated[g] = false;
            continue;
          }
        // Rounded to 1e-10 cells: the order of the sums, which depends on
        // the number of ranks, changes the mean in its last digits.
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double unit = 1e-10 * grid.cell_size()[d];
            displacements[g][d] =
              unit * std::round((sums[g * (dim + 1) + d] / n_points -
                                 grains[g].centroid[d]) /
                                unit);
          }
        translated[g] = uniform_velocity(g, displacements[g], time);
      }
  }



  template <int dim>
  Tensor<1, dim>
  RigidGrainMotion<dim>::surface_normal(const unsigned int grain,
                                        const Point<dim>  &point) const
  {
    if (!translated[grain])
      return Tensor<1, dim>();
    return outward_normal(grain_parameters[grain],
                          point - displacements[grain]);
  }



  template <int dim>
  double
  RigidGrainMotion<dim>::surface_distance(const unsigned int grain,
                                          const Point<dim>  &point) const
  {
    if (!translated[grain])
      return std::numeric_limits<double>::quiet_NaN();
    Tensor<1, dim> normal;
    return signed_distance(grain_parameters[grain],
                           point - displacements[grain],
                           normal);
  }



  template <int dim>
  bool
  RigidGrainMotion<dim>::uniform_velocity(const unsigned int    grain,
                                          const Tensor<1, dim> &displacement,
                                          const double          time) const
  {
    const auto [lower, upper] = bounding_box(grain_parameters[grain]);
    const Tensor<1, dim> centre =
      velocity(grains[grain], grains[grain].centroid + displacement, time);
    double largest = centre.norm();
    double change  = 0.;
    for (unsigned int corner = 0; corner < (1U << dim); ++corner)
      {
        Point<dim> position;
        for (unsigned int d = 0; d < dim; ++d)
          position[d] =
            ((corner & (1U << d)) ? upper[d] : lower[d]) + displacement[d];
        const Tensor<1, dim> value = velocity(grains[grain], position, time);
        largest                    = std::max(largest, value.norm());
        change                     = std::max(change, (value - centre).norm());
      }
    return change <= 1e-12 * largest;
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
