// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_output_schedule_h
#define grainmpm_postprocess_output_schedule_h

#include <grainmpm/base/parameters.h>

#include <deal.II/base/mpi.h>

#include <chrono>

namespace grainmpm
{
  /**
   * When a run writes output and checkpoints: output at every multiple of
   * `Output/Interval` (every step if 0) and at the end; checkpoints every
   * `Checkpoint/Steps between checkpoints` steps or `Minutes between
   * checkpoints` of wall-clock time (rank 0's clock decides), never at the
   * end. Counts the outputs written. Its state is written to checkpoints by
   * serialize().
   */
  class OutputSchedule
  {
  public:
    OutputSchedule(const OutputParameters     &output,
                   const CheckpointParameters &checkpoint,
                   const MPI_Comm              communicator);

    /** Whether output is due at @p time (@p at_end: the last step). */
    bool
    output_due(const double time, const bool at_end) const
    {
      return time >= next_output * (1. - 1e-12) || at_end;
    }

    /**
     * Output was written at @p time after a step of @p dt: returns its
     * index and moves the next output time past @p time.
     */
    unsigned int
    output_written(const double time, const double dt);

    /**
     * Output was written without moving the schedule (the first output, or
     * the last before an error): returns its index.
     */
    unsigned int
    extra_output_written()
    {
      return n_outputs++;
    }

    /**
     * Whether a checkpoint is due after step @p step (@p at_end: the last
     * step). Collective.
     */
    bool
    checkpoint_due(const unsigned int step, const bool at_end) const;

    /** A checkpoint was written: restart the wall clock. */
    void
    checkpoint_written()
    {
      last_checkpoint = std::chrono::steady_clock::now();
    }

    /** Read or write the state with @p archive. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &next_output &n_outputs;
    }

  private:
    const OutputParameters     &output;
    const CheckpointParameters &checkpoint;
    const MPI_Comm              communicator;

    double                                next_output = 0.;
    unsigned int                          n_outputs   = 0;
    std::chrono::steady_clock::time_point last_checkpoint;
  };
} // namespace grainmpm

#endif
