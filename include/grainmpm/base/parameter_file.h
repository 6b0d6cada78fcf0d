// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_parameter_file_h
#define grainmpm_base_parameter_file_h

#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * The formats of a parameter file that deal.II's ParameterHandler reads,
   * told by the extension of the file name.
   */
  enum class ParameterFileFormat
  {
    /** `.prm`: `subsection`/`set`/`end` lines, with `include FILE` lines. */
    prm,
    /**
     * `.json`: nested objects; an entry is a string, or an object with a
     * "value" (as ParameterHandler::print_parameters() writes it).
     */
    json,
    /**
     * `.xml`: the XML that ParameterHandler::print_parameters() writes,
     * with a root element ParameterHandler and mangled names.
     */
    xml
  };

  /**
   * The format of the parameter file @p filename. Throws an InputError if
   * the file does not exist, is not a regular file or cannot be read, if a
   * `.prm` file includes itself or a file that does not exist, and if the
   * extension is none of `.prm`, `.json` and `.xml`.
   */
  ParameterFileFormat
  check_parameter_file(const std::string &filename);

  /**
   * The names of the subsections nested directly in subsection @p parent of
   * the parameter file @p filename (following `include` lines of a `.prm`
   * file). Used to declare "any number" of materials and grains before
   * parsing.
   */
  std::vector<std::string>
  find_subsections(const std::string &filename, const std::string &parent);

  /**
   * The subsection path ("Materials/elastic") in force at line @p line of
   * the `.prm` file @p filename (not following `include`s, as line numbers
   * count within one file). Empty at the top level. Used to name the entry
   * of a pattern error, which deal.II reports by line only.
   */
  std::string
  subsection_path_at_line(const std::string &filename, const unsigned int line);

  /**
   * Check @p filename (check_parameter_file()) and read only its entry
   * "Dimension".
   */
  unsigned int
  read_dimension(const std::string &filename);

  /**
   * The text of the parameter file @p filename as a run reads it: for a
   * `.prm` file with each `include` line replaced by the text of the file it
   * names (recursively), between comment lines that name it, a copy that
   * runs from anywhere; a `.json` or `.xml` file as it is.
   */
  std::string
  expand_includes(const std::string &filename);

  /**
   * The name under which a run records its input file @p filename in the
   * output directory: `original.prm`, `original.json` or `original.xml`.
   */
  std::string
  original_file_name(const std::string &filename);
} // namespace grainmpm

#endif
