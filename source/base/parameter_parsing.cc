// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>

#include <deal.II/base/utilities.h>

namespace grainmpm
{
  std::string
  strip_comment(const std::string &line)
  {
    return dealii::Utilities::trim(line.substr(0, line.find('#')));
  }



  std::vector<double>
  parse_numbers(const std::string &text,
                const std::string &entry,
                const std::string &separator)
  {
    std::vector<double> numbers;
    for (const auto &item :
         dealii::Utilities::split_string_list(text, separator))
      {
        try
          {
            numbers.push_back(dealii::Utilities::string_to_double(item));
          }
        catch (...)
          {
            throw InputError(entry,
                             "'" + item + "' in '" + text +
                               "' is not a number.");
          }
      }
    return numbers;
  }
} // namespace grainmpm
