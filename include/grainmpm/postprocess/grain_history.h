// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_grain_history_h
#define grainmpm_postprocess_grain_history_h

#include <grainmpm/base/config.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Rigid-body description of one grain from its material points.
   */
  template <int dim>
  struct GrainMotion
  {
    double         mass = 0.;
    Point<dim>     centre_of_mass;
    Tensor<1, dim> velocity;
    /** Angular velocity about the centre of mass: the z component in 2D. */
    Tensor<1, dim == 2 ? 1 : 3> angular_velocity;
    /**
     * Largest distance of a material point from the centre of mass: a
     * particle that spalls off the grain makes it grow beyond the radius.
     */
    double max_distance = 0.;
  };

  /**
   * Writes `grains.csv`: one row per grain and output time with the centre
   * of mass, the mean velocity and the angular velocity omega solving
   * I omega = L about the centre of mass.
   */
  template <int dim>
  class GrainHistory
  {
  public:
    GrainHistory(const std::string   &filename,
                 const unsigned int   n_grains,
                 const MPI_Comm       communicator,
                 const std::uintmax_t resume_length = 0);

    /** The length of the file so far (for a checkpoint). */
    std::uintmax_t
    length();

    /** The motion of every grain. */
    std::vector<GrainMotion<dim>>
    compute(const Particles::ParticleHandler<dim> &particle_handler) const;

    /**
     * Stop every rank with a message naming the file if a write has failed.
     * Collective.
     */
    void
    check_written() const;

    /** Append the rows of time @p time. */
    void
    write(const Particles::ParticleHandler<dim> &particle_handler,
          const double                           time);

  private:
    const unsigned int n_grains;
    const MPI_Comm     communicator;
    const std::string  filename;
    std::ofstream      file;
  };
} // namespace grainmpm

#endif
