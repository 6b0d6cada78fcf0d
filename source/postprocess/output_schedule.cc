// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/output_schedule.h>

namespace grainmpm
{
  OutputSchedule::OutputSchedule(const OutputParameters     &output,
                                 const CheckpointParameters &checkpoint,
                                 const MPI_Comm              communicator)
    : output(output)
    , checkpoint(checkpoint)
    , communicator(communicator)
    , next_output(output.interval)
    , last_checkpoint(std::chrono::steady_clock::now())
  {}



  unsigned int
  OutputSchedule::output_written(const double time, const double dt)
  {
    while (next_output <= time * (1. + 1e-12))
      next_output += (output.interval > 0. ? output.interval : dt);
    return n_outputs++;
  }



  bool
  OutputSchedule::checkpoint_due(const unsigned int step,
                                 const bool         at_end) const
  {
    // (The ranks' clocks differ: rank 0 decides.)
    return !at_end && ((checkpoint.steps_between > 0 &&
                        step % checkpoint.steps_between == 0) ||
                       (checkpoint.minutes_between > 0. &&
                        Utilities::MPI::broadcast(
                          communicator,
                          std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - last_checkpoint)
                              .count() >= 60. * checkpoint.minutes_between)));
  }
} // namespace grainmpm
