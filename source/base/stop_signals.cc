// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/stop_signals.h>

#include <deal.II/base/mpi.h>

#include <csignal>

namespace grainmpm
{
  namespace
  {
    /** The stop signal received (SIGTERM, SIGINT), or 0. */
    volatile std::sig_atomic_t stop_signal = 0;

    extern "C" void
    record_stop_signal(int signal)
    {
      stop_signal = signal;
      // A second one stops at once.
      std::signal(signal, SIG_DFL);
    }
  } // namespace



  StopSignals::StopSignals()
  {
    stop_signal        = 0;
    previous_terminate = std::signal(SIGTERM, record_stop_signal);
    previous_interrupt = std::signal(SIGINT, record_stop_signal);
  }



  StopSignals::~StopSignals()
  {
    std::signal(SIGTERM, previous_terminate);
    std::signal(SIGINT, previous_interrupt);
  }



  int
  StopSignals::received(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::max(static_cast<int>(stop_signal),
                                       communicator);
  }
} // namespace grainmpm
