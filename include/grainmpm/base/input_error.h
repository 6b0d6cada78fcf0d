// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_input_error_h
#define grainmpm_base_input_error_h

#include <deal.II/base/mpi.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * An error the user can fix: a wrong entry in the parameter file, a grain
   * that does not fit the grid, a particle that left the domain. The message
   * names the parameter (as "Subsection/Entry = value") or the object
   * (grain, particle) that caused it. `main()` prints it and returns 1.
   */
  class InputError : public std::runtime_error
  {
  public:
    /**
     * An error about the entry @p entry (a path such as
     * "Grains/Grain 1/Material") with the explanation @p message.
     */
    InputError(const std::string &entry, const std::string &message)
      : std::runtime_error(entry.empty() ? message : entry + ": " + message)
    {}
  };



  /**
   * Throw the InputError @p error on every rank of @p communicator if some
   * rank has one (the lowest such rank's message), so that all ranks stop
   * together instead of waiting for each other in a collective call.
   * Collective; @p error is empty where there is nothing to report.
   */
  inline void
  throw_on_all_ranks(const std::string &error, const MPI_Comm communicator)
  {
    const unsigned int any =
      dealii::Utilities::MPI::max(error.empty() ? 0U : 1U, communicator);
    if (any == 0)
      return;
    for (const std::string &message :
         dealii::Utilities::MPI::all_gather(communicator, error))
      if (!message.empty())
        throw InputError("", message);
  }
} // namespace grainmpm

#endif
