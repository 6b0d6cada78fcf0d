// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_reaction_history_h
#define grainmpm_postprocess_reaction_history_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/postprocess/history_file.h>
#include <grainmpm/postprocess/inertial_number.h>

#include <deal.II/base/point.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Writes `walls.csv`: one row per step with the force that the grains
   * exert on every closed box face and on every rigid grain, and the
   * torque on each rigid grain about its centre of mass. The force is the
   * reaction of the constraint impulses of the step (ConstraintImpulses,
   * summed over the ranks) divided by the step: its time integral over any
   * interval is what the walls and rigid grains took of the grains'
   * momentum, whatever the scheme. For every rigid grain it also writes
   * the inertial number of its loading (InertialNumber).
   */
  template <int dim>
  class ReactionHistory
  {
  public:
    /**
     * @p centres: the centres of mass of the grains at the start (those of
     * the rigid grains are kept and moved with their prescribed velocity);
     * @p particle_handler: the material points at the start. Collective.
     */
    ReactionHistory(const std::string                     &filename,
                    const BackgroundGrid<dim>             &grid,
                    const std::vector<GrainInfo<dim>>     &grains,
                    const std::vector<Point<dim>>         &centres,
                    const Particles::ParticleHandler<dim> &particle_handler,
                    const MPI_Comm                         communicator,
                    const std::uintmax_t                   resume_length = 0);

    /** The length of the file so far (for a checkpoint). */
    std::uintmax_t
    length();

    /**
     * Checkpoint the centres of the rigid grains and the extents of the
     * inertial number.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &centres &inertial_number;
    }

    /**
     * Append the row of step @p step, which ended at @p time after a step
     * of @p dt with the constraint impulses @p impulses of this rank and
     * the material points of @p particle_handler, after moving the centres
     * of the rigid grains to @p time. Collective.
     */
    void
    write_row(const unsigned int                     step,
              const double                           time,
              const double                           dt,
              const ConstraintImpulses<dim>         &impulses,
              const Particles::ParticleHandler<dim> &particle_handler);

    /**
     * Stop every rank with a message naming the file if a write has failed.
     * Collective.
     */
    void
    check_written() const;

  private:
    const BackgroundGrid<dim>         &grid;
    const std::vector<GrainInfo<dim>> &grains;
    const MPI_Comm                     communicator;
    HistoryFile                        file;
    /** The closed faces (open faces take no force). */
    std::vector<unsigned int> faces;
    /** The rigid grains and their centres of mass at the current time. */
    std::vector<unsigned int> rigid_grains;
    std::vector<Point<dim>>   centres;
    /** The inertial number of the rigid grains' loading. */
    InertialNumber<dim> inertial_number;
  };
} // namespace grainmpm

#endif
