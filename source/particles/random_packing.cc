// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/random_packing.h>

#include <cmath>
#include <limits>
#include <random>

namespace grainmpm
{
  template <int dim>
  std::vector<GrainParameters<dim>>
  random_packing(const RandomPackingParameters<dim> &parameters)
  {
    const Point<dim> &lower    = parameters.lower_corner;
    const Point<dim> &upper    = parameters.upper_corner;
    const double      r_min    = parameters.minimum_radius;
    const double      r_max    = parameters.maximum_radius;
    const double      factor   = 1. + parameters.gap;
    constexpr int     vertical = 1;

    // Lateral directions and the columns that bucket grains by their
    // lateral position (width 2 r_max factor: a grain's neighbours lie in
    // its own and the adjacent columns).
    std::vector<unsigned int> lateral;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != vertical)
        lateral.push_back(d);
    const double              width = 2. * r_max * factor;
    std::vector<unsigned int> n_columns;
    unsigned int              n_total = 1;
    for (const unsigned int d : lateral)
      {
        n_columns.push_back(
          std::max(1U,
                   static_cast<unsigned int>((upper[d] - lower[d]) / width)));
        n_total *= n_columns.back();
      }
    const auto column_of = [&](const Point<dim> &x, std::vector<int> &index) {
      index.resize(lateral.size());
      for (unsigned int k = 0; k < lateral.size(); ++k)
        {
          const double size =
            (upper[lateral[k]] - lower[lateral[k]]) / n_columns[k];
          index[k] =
            std::min<int>(n_columns[k] - 1,
                          static_cast<int>((x[lateral[k]] - lower[lateral[k]]) /
                                           size));
        }
    };
    std::vector<std::vector<unsigned int>> columns(n_total);

    std::mt19937 generator(parameters.seed);
    const auto   uniform = [&generator](const double a, const double b) {
      return a + (b - a) * ((generator() + 0.5) / 4294967296.);
    };

    std::vector<GrainParameters<dim>> grains;

    // The lowest height at which a grain of radius r dropped at the lateral
    // position of centre touches nothing: on the floor, or resting on a
    // grain whose lateral distance is below the sum of the radii.
    const auto resting_height = [&](const Point<dim> &centre, const double r) {
      std::vector<int> index;
      double           height = lower[vertical] + r;
      column_of(centre, index);
      const unsigned int reach = (lateral.size() == 1) ? 3 : 9;
      for (unsigned int k = 0; k < reach; ++k)
        {
          std::vector<int> neighbour(index);
          neighbour[0] += static_cast<int>(k % 3) - 1;
          if (lateral.size() == 2)
            neighbour[1] += static_cast<int>(k / 3) - 1;
          bool inside = true;
          int  flat   = 0;
          for (unsigned int l = lateral.size(); l-- > 0;)
            {
              inside = inside && neighbour[l] >= 0 &&
                       neighbour[l] < static_cast<int>(n_columns[l]);
              flat = flat * static_cast<int>(n_columns[l]) + neighbour[l];
            }
          if (!inside)
            continue;
          for (const unsigned int j : columns[flat])
            {
              const double distance       = (r + grains[j].radius) * factor;
              double       lateral_square = 0.;
              for (const unsigned int d : lateral)
                lateral_square += (centre[d] - grains[j].centre[d]) *
                                  (centre[d] - grains[j].centre[d]);
              if (lateral_square < distance * distance)
                height =
                  std::max(height,
                           grains[j].centre[vertical] +
                             std::sqrt(distance * distance - lateral_square));
            }
        }
      return height;
    };

    std::vector<int> index;
    for (unsigned int g = 0; g < parameters.n_grains; ++g)
      {
        const double r = uniform(r_min, r_max);

        // Drop the grain at several random lateral positions and keep the
        // lowest resting place: holes get filled, and the packing is dense.
        Point<dim> centre;
        double     height = std::numeric_limits<double>::max();
        for (unsigned int attempt = 0; attempt < parameters.n_candidates;
             ++attempt)
          {
            Point<dim> candidate;
            for (const unsigned int d : lateral)
              candidate[d] = uniform(lower[d] + r, upper[d] - r);
            const double rest = resting_height(candidate, r);
            if (rest < height)
              {
                height = rest;
                centre = candidate;
              }
          }
        if (height + r > upper[vertical])
          throw InputError(
            "Random packing/Upper corner",
            "the box is full after " + std::to_string(g) + " of " +
              std::to_string(parameters.n_grains) +
              " grains: raise the upper corner, or lower 'Number of "
              "grains' or the radii.");
        centre[vertical] = height;

        GrainParameters<dim> grain;
        grain.source     = "Random packing, grain " + std::to_string(g + 1);
        grain.shape_text = (dim == 2 ? "disk" : "sphere");
        grain.centre     = centre;
        grain.radius     = r;
        grain.material   = parameters.material;
        grain.initial_velocity = (dim == 2 ? "0; 0" : "0; 0; 0");
        column_of(centre, index);
        int flat = 0;
        for (unsigned int l = lateral.size(); l-- > 0;)
          flat = flat * static_cast<int>(n_columns[l]) + index[l];
        columns[flat].push_back(grains.size());
        grains.push_back(grain);
      }
    return grains;
  }



  template <int dim>
  void
  add_random_packing(Parameters<dim> &parameters)
  {
    auto &grains = parameters.grains;
    grains.erase(grains.end() - parameters.n_packed_grains, grains.end());
    parameters.n_packed_grains = 0;
    if (parameters.random_packing.n_grains == 0)
      return;

    auto packed = random_packing(parameters.random_packing);
    for (auto &grain : packed)
      parameters.check_grain(grain);
    grains.insert(grains.end(), packed.begin(), packed.end());
    parameters.n_packed_grains = packed.size();
  }



  template std::vector<GrainParameters<2>>
  random_packing<2>(const RandomPackingParameters<2> &);
  template std::vector<GrainParameters<3>>
  random_packing<3>(const RandomPackingParameters<3> &);
  template void
  add_random_packing<2>(Parameters<2> &);
  template void
  add_random_packing<3>(Parameters<3> &);
} // namespace grainmpm
