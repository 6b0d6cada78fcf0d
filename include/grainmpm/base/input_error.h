// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_input_error_h
#define grainmpm_base_input_error_h

#include <stdexcept>
#include <string>

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
} // namespace grainmpm

#endif
