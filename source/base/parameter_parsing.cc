// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>

#include <deal.II/base/utilities.h>

#include <cmath>

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
        const std::string quoted =
          "'" + item + "'" + (item == text ? "" : " in '" + text + "'");
        double number = 0.;
        try
          {
            number = dealii::Utilities::string_to_double(item);
          }
        catch (...)
          {
            throw InputError(entry, quoted + " is not a number.");
          }
        if (!std::isfinite(number))
          throw InputError(entry, quoted + " is not a finite number.");
        numbers.push_back(number);
      }
    return numbers;
  }
} // namespace grainmpm
