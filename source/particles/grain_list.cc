// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/particles/grain_list.h>

#include <deal.II/base/utilities.h>

#include <fstream>
#include <iomanip>

namespace grainmpm
{
  template <int dim>
  std::vector<GrainParameters<dim>>
  read_grain_list(const std::string &filename)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("Grains/Grain list file = " + filename,
                       "cannot open this file.");
    std::vector<GrainParameters<dim>> grains;
    std::string                       line;
    unsigned int                      line_number = 0;
    while (std::getline(in, line))
      {
        ++line_number;
        line = strip_comment(line);
        if (line.empty())
          continue;
        const std::string source = "Grains/Grain list file " + filename +
                                   ", line " + std::to_string(line_number);
        const auto fields = dealii::Utilities::split_string_list(line, ',');
        const unsigned int n_fields = 1 + dim + 1 + dim + 1 + 1 + dim;
        if (fields.size() != n_fields)
          throw InputError(source,
                           "expected " + std::to_string(n_fields) +
                             " comma-separated columns (shape, centre, "
                             "radius, size, rotation, material, "
                             "velocity), found " +
                             std::to_string(fields.size()) + ".");
        GrainParameters<dim> grain;
        grain.source        = source;
        grain.shape_text    = fields[0];
        unsigned int column = 1;
        for (unsigned int d = 0; d < dim; ++d)
          grain.centre[d] = parse_numbers(fields[column++], source)[0];
        grain.radius = parse_numbers(fields[column++], source)[0];
        for (unsigned int d = 0; d < dim; ++d)
          grain.size[d] = parse_numbers(fields[column++], source)[0];
        grain.rotation = parse_numbers(fields[column++], source)[0];
        grain.material = fields[column++];
        grain.initial_velocity.clear();
        for (unsigned int d = 0; d < dim; ++d)
          grain.initial_velocity += (d > 0 ? ";" : "") + fields[column++];
        grains.push_back(grain);
      }
    return grains;
  }



  template <int dim>
  void
  write_grain_list(std::ostream                            &out,
                   const std::vector<GrainParameters<dim>> &grains)
  {
    out << "# shape, centre (" << dim << "), radius, size (" << dim
        << "), rotation [degrees], material, velocity (" << dim << ")\n"
        << std::setprecision(12);
    for (const auto &grain : grains)
      {
        out << grain.shape_text;
        for (unsigned int d = 0; d < dim; ++d)
          out << ", " << grain.centre[d];
        out << ", " << grain.radius;
        for (unsigned int d = 0; d < dim; ++d)
          out << ", " << grain.size[d];
        out << ", " << grain.rotation << ", " << grain.material;
        const auto velocity =
          dealii::Utilities::split_string_list(grain.initial_velocity, ';');
        for (unsigned int d = 0; d < dim; ++d)
          out << ", " << (d < velocity.size() ? velocity[d] : "0");
        out << '\n';
      }
  }



  template std::vector<GrainParameters<2>>
  read_grain_list<2>(const std::string &);
  template std::vector<GrainParameters<3>>
  read_grain_list<3>(const std::string &);
  template void
  write_grain_list<2>(std::ostream &, const std::vector<GrainParameters<2>> &);
  template void
  write_grain_list<3>(std::ostream &, const std::vector<GrainParameters<3>> &);
} // namespace grainmpm
