// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_parameter_parsing_h
#define grainmpm_base_parameter_parsing_h

#include <grainmpm/base/input_error.h>

#include <string>
#include <utility>
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
   * InputError naming @p entry if an item is not a finite number.
   */
  std::vector<double>
  parse_numbers(const std::string &text,
                const std::string &entry,
                const std::string &separator = ",");

  /**
   * The value that @p names gives to the text @p text of a choice (the
   * text of a Patterns::Selection entry, or an item of a list entry), for
   * example
   * @code
   *   model = parse_choice<ContactModel>(
   *     "Contact/Contact model = " + model_text,
   *     model_text,
   *     {{"none", ContactModel::none},
   *      {"frictionless", ContactModel::frictionless},
   *      {"Coulomb friction", ContactModel::coulomb_friction}});
   * @endcode
   * Throws an InputError naming @p entry (the entry and its value) if @p text
   * is none of the names, with the message @p message or, if that is empty,
   * "unknown choice (use 'a', 'b' or 'c')." listing the names.
   */
  template <typename Enum>
  Enum
  parse_choice(const std::string                               &entry,
               const std::string                               &text,
               const std::vector<std::pair<std::string, Enum>> &names,
               const std::string                               &message = "")
  {
    for (const auto &name : names)
      if (name.first == text)
        return name.second;

    std::string choices;
    for (unsigned int i = 0; i < names.size(); ++i)
      choices +=
        std::string(i == 0 ? "" : (i + 1 < names.size() ? ", " : " or ")) +
        "'" + names[i].first + "'";
    throw InputError(entry,
                     message.empty() ? "unknown choice (use " + choices + ")." :
                                       message);
  }
} // namespace grainmpm

#endif
