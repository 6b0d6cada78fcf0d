// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_grain_list_h
#define grainmpm_particles_grain_list_h

#include <grainmpm/particles/grain_parameters.h>

#include <ostream>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Read the grain list file @p filename ('Grains/Grain list file'): one
   * grain per line with the comma-separated columns shape, centre (dim
   * numbers), radius, size (dim numbers), rotation in degrees, material
   * name and velocity (dim expressions); '#' starts a comment. Each grain's
   * source names the file and the line. The grains are not checked yet
   * (GrainParameters::check() and Parameters::check() do that).
   *
   * Throws InputError if the file cannot be opened, a line does not have
   * the number of columns above or a number does not parse.
   */
  template <int dim>
  std::vector<GrainParameters<dim>>
  read_grain_list(const std::string &filename);

  /**
   * Write @p grains as a grain list CSV (the format of 'Grains/Grain list
   * file'), with a header comment.
   */
  template <int dim>
  void
  write_grain_list(std::ostream                            &out,
                   const std::vector<GrainParameters<dim>> &grains);
} // namespace grainmpm

#endif
