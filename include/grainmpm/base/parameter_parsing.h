// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_parameter_parsing_h
#define grainmpm_base_parameter_parsing_h

#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * @p line without a comment (from the first '#' on) and without leading
   * and trailing white space.
   */
  std::string
  strip_comment(const std::string &line);

  /**
   * The numbers of the @p separator-separated list @p text. Throws an
   * InputError naming @p entry if an item is not a number.
   */
  std::vector<double>
  parse_numbers(const std::string &text,
                const std::string &entry,
                const std::string &separator = ",");
} // namespace grainmpm

#endif
