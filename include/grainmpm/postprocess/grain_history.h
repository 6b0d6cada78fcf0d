// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_grain_history_h
#define grainmpm_postprocess_grain_history_h

#include <grainmpm/base/config.h>
#include <grainmpm/postprocess/history_file.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/serialization/vector.hpp>

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
    /**
     * Mass-weighted mean of the points' deformation gradients F (the
     * identity for rigid grains, whose points do not deform).
     */
    Tensor<2, dim> deformation_gradient;
  };

  /**
   * Writes `grains.csv`: one row per grain and output time with the centre
   * of mass, the mean velocity, the angular velocity omega solving
   * I omega = L about the centre of mass, the rotation since the start and
   * the coordination number.
   *
   * The rotation of a deformable grain is that of the polar decomposition
   * of its mean deformation gradient, which the points integrate from the
   * velocity gradient every step. In 2D it is an angle counted on through
   * whole turns: between outputs it is predicted from the angular velocity
   * (trapezoidal rule) and corrected to the decomposition, so a grain may
   * turn by anything short of a half turn more than the prediction between
   * two outputs. In 3D it is the rotation vector (axis times angle, angle
   * at most pi). Rigid grains, whose points carry F = I, integrate their
   * angular velocity by the trapezoidal rule between outputs.
   */
  template <int dim>
  class GrainHistory
  {
  public:
    /** @p rigid says for every grain whether it is rigid. */
    GrainHistory(const std::string       &filename,
                 const std::vector<bool> &rigid,
                 const MPI_Comm           communicator,
                 const std::uintmax_t     resume_length = 0);

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

    /**
     * Update the rotations to time @p time from the @p motions computed
     * then (every rank) and, if @p write_rows, append the rows of that time
     * with the @p coordination_numbers (rank 0).
     */
    void
    write(const std::vector<GrainMotion<dim>> &motions,
          const std::vector<unsigned int>     &coordination_numbers,
          const double                         time,
          const bool                           write_rows = true);

    /** Checkpoint the rotations and the last output's angular velocities. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &rotations &last_angular_velocities &last_time &have_last;
    }

  private:
    /** Update #rotations to @p time from @p motions. */
    void
    update_rotations(const std::vector<GrainMotion<dim>> &motions,
                     const double                         time);

    const std::vector<bool> rigid;
    const unsigned int      n_grains;
    const MPI_Comm          communicator;
    HistoryFile             file;

    using Rotation = Tensor<1, dim == 2 ? 1 : 3>;
    /** Rotation of each grain since the start (see the class text). */
    std::vector<Rotation> rotations;
    /** Angular velocities and time of the last output. */
    std::vector<Rotation> last_angular_velocities;
    double                last_time = 0.;
    bool                  have_last = false;
  };
} // namespace grainmpm

#endif
