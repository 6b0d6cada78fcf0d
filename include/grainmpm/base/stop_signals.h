// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_stop_signals_h
#define grainmpm_base_stop_signals_h

#include <grainmpm/base/config.h>

#include <mpi.h>

namespace grainmpm
{
  /**
   * While an object of this class lives, SIGTERM and SIGINT (a batch
   * system's time limit, Ctrl-C) are recorded instead of killing the
   * process, so that the time loop can stop cleanly after the step; a second
   * signal of the same kind stops the process at once. The handlers that
   * were installed before are restored by the destructor.
   */
  class StopSignals
  {
  public:
    StopSignals();

    ~StopSignals();

    StopSignals(const StopSignals &) = delete;
    StopSignals &
    operator=(const StopSignals &) = delete;

    /** The signal received on any rank of @p communicator, or 0. Collective. */
    static int
    received(const MPI_Comm communicator);

  private:
    void (*previous_terminate)(int);
    void (*previous_interrupt)(int);
  };
} // namespace grainmpm

#endif
