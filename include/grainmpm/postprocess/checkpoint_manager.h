// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_checkpoint_manager_h
#define grainmpm_postprocess_checkpoint_manager_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Writes and reads checkpoints: a directory checkpoint-NNNNNN (the step)
   * in the output directory with the triangulation and the material points
   * (deal.II serialization, any number of ranks) and a file `state` with
   * the run's own state (a boost binary archive written by rank 0). A
   * checkpoint is written to a temporary directory that is renamed when
   * complete, so a run killed meanwhile leaves the older ones intact; the
   * newest `Number of checkpoints kept` are kept, including those of the
   * run a resumed run continues.
   */
  template <int dim>
  class CheckpointManager
  {
  public:
    CheckpointManager(const CheckpointParameters &parameters,
                      const std::string          &output_directory,
                      const MPI_Comm              communicator);

    /**
     * Whether the run resumes from a checkpoint (`Resume from`). If so, the
     * constructor has opened its state: read it with resume_archive().
     */
    bool
    resuming() const
    {
      return resume_state != nullptr;
    }

    /** The state archive of the checkpoint the run resumes from. */
    boost::archive::binary_iarchive &
    resume_archive()
    {
      return *resume_state;
    }

    /**
     * Replace the material points of @p particle_handler and the cells of
     * @p grid by those of the checkpoint the run resumes from.
     */
    void
    load(BackgroundGrid<dim>             &grid,
         Particles::ParticleHandler<dim> &particle_handler) const;

    /** Close the checkpoint the run resumed from. */
    void
    finish_resume();

    /**
     * Write checkpoint-@p step: @p grid with the material points of
     * @p particle_handler, and the state written by @p write_state on
     * rank 0. Collective.
     */
    void
    write(const unsigned int               step,
          const BackgroundGrid<dim>       &grid,
          Particles::ParticleHandler<dim> &particle_handler,
          const std::function<void(boost::archive::binary_oarchive &)>
            &write_state);

  private:
    const CheckpointParameters &parameters;
    const std::string           directory;
    const MPI_Comm              communicator;

    std::ifstream                                    resume_stream;
    std::unique_ptr<boost::archive::binary_iarchive> resume_state;
    /** The checkpoints kept, oldest first (rank 0). */
    std::vector<std::string> checkpoints;
  };
} // namespace grainmpm

#endif
