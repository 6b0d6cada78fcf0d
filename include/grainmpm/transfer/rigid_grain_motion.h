// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_rigid_grain_motion_h
#define grainmpm_transfer_rigid_grain_motion_h

#include <grainmpm/base/config.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/grain_parameters.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/serialization/vector.hpp>

#include <limits>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * The motion of the rigid grains, which move with their prescribed
   * velocity u(x, t) (`Grains/<name>/Prescribed velocity`), shared by the
   * grid nodes of their velocity fields (prescribe(), for the contact), by
   * their material points (move_point(), for the grid-to-particle update)
   * and by their centres (move(), for the reactions): the velocity at a
   * point and time, the midpoint rule x <- x + dt u(x, t + dt/2), and the
   * check that u is finite wherever and whenever it is used, with one
   * InputError for nodes and points alike.
   */
  template <int dim>
  class RigidGrainMotion
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * The motion of the rigid ones among @p grains, on @p grid;
     * @p grain_parameters (one per grain) name their entries in the
     * errors.
     */
    RigidGrainMotion(const std::vector<GrainInfo<dim>>       &grains,
                     const std::vector<GrainParameters<dim>> &grain_parameters,
                     const BackgroundGrid<dim>               &grid);

    /** The prescribed velocity of @p grain at @p point at @p time. */
    static Tensor<1, dim>
    velocity(const GrainInfo<dim> &grain,
             const Point<dim>     &point,
             const double          time);

    /**
     * The point @p point of the rigid grain @p grain moved over a step of
     * @p dt by the midpoint rule: @p point + @p dt u(@p point,
     * @p midpoint_time).
     */
    static Point<dim>
    move(const GrainInfo<dim> &grain,
         const Point<dim>     &point,
         const double          midpoint_time,
         const double          dt);

    /**
     * Set the slots of the rigid fields of @p layout in @p velocities (dim
     * per slot) to the prescribed velocities at their nodes at @p time (a
     * rigid grain has a field of its own, with its index). Throws on all
     * ranks the InputError of a velocity that is not finite. Collective.
     */
    void
    prescribe(const GrainFieldLayout<dim> &layout,
              VectorType                  &velocities,
              const double                 time) const;

    /**
     * Move the material point @p id of the rigid grain @p grain from
     * @p old_position over the step from @p time by @p dt: @p new_position
     * by move() at the midpoint of the step, @p new_velocity the velocity
     * there at @p time + @p dt. Returns the message of the InputError if
     * one of them is not finite, else an empty string.
     */
    std::string
    move_point(const unsigned int          grain,
               const types::particle_index id,
               const Point<dim>           &old_position,
               const double                time,
               const double                dt,
               Point<dim>                 &new_position,
               Tensor<1, dim>             &new_velocity) const;

    /**
     * Locate the rigid grains at @p time, the start of a step of @p dt: a
     * rigid grain that has so far only been translated (its prescribed
     * velocity uniform over it at every step, and, when its points were
     * counted, none of them lost) is its shape moved by the displacement of
     * its points' mean from its GrainInfo::centroid. The displacement is
     * carried from one step to the next as the points move (dt u at the
     * midpoint); the points themselves are summed at the first call and
     * whenever @p time is neither the last call's time nor the end of its
     * step (steps taken by another stepper). Collective.
     */
    void
    locate(const Particles::ParticleHandler<dim> &particle_handler,
           const double                           time,
           const double                           dt);

    /**
     * The outward unit normal of the rigid grain @p grain seen from
     * @p point (outward_normal() of its shape where locate() found it),
     * or zero if its shape has not been located.
     */
    Tensor<1, dim>
    surface_normal(const unsigned int grain, const Point<dim> &point) const;

    /**
     * The signed distance of @p point from the surface of the rigid grain
     * @p grain (signed_distance() of its shape where locate() found it,
     * negative inside), or NaN if its shape has not been located.
     */
    double
    surface_distance(const unsigned int grain, const Point<dim> &point) const;

    /**
     * Write or read what locate() carries from step to step (for
     * checkpoints: a resumed run then locates the grains as the run it
     * resumes would have, to the last bit).
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &translated &displacements &located_time &located_dt;
    }

  private:
    /**
     * The displacements of the translated rigid grains from the mean of
     * their material points in @p particle_handler at @p time (a grain
     * that has lost points is no longer located). Collective.
     */
    void
    locate_from_points(const Particles::ParticleHandler<dim> &particle_handler,
                       const double                           time);

    /**
     * Whether the prescribed velocity of @p grain at @p time is the same at
     * the corners of its bounding box moved by @p displacement as at its
     * centroid (to round-off).
     */
    bool
    uniform_velocity(const unsigned int    grain,
                     const Tensor<1, dim> &displacement,
                     const double          time) const;

    /**
     * The message of the InputError for the prescribed velocity of the
     * rigid grain @p grain that is not finite at @p time (at the end of a
     * step of @p dt if @p dt > 0) at @p where, at @p position.
     */
    std::string
    not_finite(const unsigned int grain,
               const double       time,
               const double       dt,
               const std::string &where,
               const Point<dim>  &position) const;

    const std::vector<GrainInfo<dim>>       &grains;
    const std::vector<GrainParameters<dim>> &grain_parameters;
    const BackgroundGrid<dim>               &grid;
    const bool                               has_rigid_grains;

    /**
     * Per grain: whether it is a rigid grain that has only been translated
     * (locate()), and the displacement of its points' mean.
     */
    std::vector<bool>           translated;
    std::vector<Tensor<1, dim>> displacements;
    /** The time and step of the last locate() (NaN: none yet). */
    double located_time = std::numeric_limits<double>::quiet_NaN();
    double located_dt   = 0.;
  };
} // namespace grainmpm

#endif
