// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/random_packing.h>

#include <cmath>
#include <limits>
#include <random>

namespace grainmpm
{
  namespace
  {
    /**
     * The deposited grains bucketed by their lateral position into columns
     * of width @p width (2 Maximum radius (1 + Gap): a grain's neighbours
     * lie in its own column and the adjacent ones), and where a grain
     * dropped onto them lands.
     */
    template <int dim>
    class DepositionColumns
    {
    public:
      static constexpr int vertical = 1;

      DepositionColumns(const Point<dim> &lower,
                        const Point<dim> &upper,
                        const double      width)
        : lower(lower)
        , upper(upper)
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (d != vertical)
            lateral.push_back(d);
        unsigned int n_total = 1;
        for (const unsigned int d : lateral)
          {
            n_columns.push_back(std::max(
              1U, static_cast<unsigned int>((upper[d] - lower[d]) / width)));
            n_total *= n_columns.back();
          }
        columns.resize(n_total);
      }

      /** The directions normal to the vertical. */
      const std::vector<unsigned int> &
      lateral_directions() const
      {
        return lateral;
      }

      /** Record grain number @p g, at @p centre. */
      void
      add(const Point<dim> &centre, const unsigned int g)
      {
        std::vector<int> index;
        column_of(centre, index);
        columns[flat(index)].push_back(g);
      }

      /**
       * The lowest height at which a grain of radius @p r dropped at the
       * lateral position of @p centre touches nothing of @p grains
       * (contact distance (r + r_j) @p factor): on the floor, or resting on
       * a grain whose lateral distance is below the contact distance; that
       * grain in @p support (-1: the floor).
       */
      double
      resting_height(const std::vector<GrainParameters<dim>> &grains,
                     const Point<dim>                        &centre,
                     const double                             r,
                     const double                             factor,
                     int                                     *support) const
      {
        std::vector<int> index;
        double           height = lower[vertical] + r;
        *support                = -1;
        column_of(centre, index);
        const unsigned int reach = (lateral.size() == 1) ? 3 : 9;
        for (unsigned int k = 0; k < reach; ++k)
          {
            std::vector<int> neighbour(index);
            neighbour[0] += static_cast<int>(k % 3) - 1;
            if (lateral.size() == 2)
              neighbour[1] += static_cast<int>(k / 3) - 1;
            const int column = flat(neighbour);
            if (column < 0)
              continue;
            for (const unsigned int j : columns[column])
              {
                const double distance       = (r + grains[j].radius) * factor;
                double       lateral_square = 0.;
                for (const unsigned int d : lateral)
                  lateral_square += (centre[d] - grains[j].centre[d]) *
                                    (centre[d] - grains[j].centre[d]);
                if (!(lateral_square < distance * distance))
                  continue;
                const double on_j =
                  grains[j].centre[vertical] +
                  std::sqrt(distance * distance - lateral_square);
                if (on_j > height)
                  {
                    height   = on_j;
                    *support = static_cast<int>(j);
                  }
              }
          }
        return height;
      }

    private:
      void
      column_of(const Point<dim> &x, std::vector<int> &index) const
      {
        index.resize(lateral.size());
        for (unsigned int k = 0; k < lateral.size(); ++k)
          {
            const double size =
              (upper[lateral[k]] - lower[lateral[k]]) / n_columns[k];
            index[k] =
              std::min<int>(n_columns[k] - 1,
                            static_cast<int>(
                              (x[lateral[k]] - lower[lateral[k]]) / size));
          }
      }

      /** The column of the lateral indices @p index; -1 outside the box. */
      int
      flat(const std::vector<int> &index) const
      {
        int column = 0;
        for (unsigned int l = lateral.size(); l-- > 0;)
          {
            if (index[l] < 0 || index[l] >= static_cast<int>(n_columns[l]))
              return -1;
            column = column * static_cast<int>(n_columns[l]) + index[l];
          }
        return column;
      }

      const Point<dim>                       lower, upper;
      std::vector<unsigned int>              lateral;
      std::vector<unsigned int>              n_columns;
      std::vector<std::vector<unsigned int>> columns;
    };



    /**
     * Rolling deposition (2D): a disk of radius @p r dropped onto the
     * packing @p grains rests at @p centre on the grain @p support (-1: the
     * floor). It rolls down over its support, away from the support's
     * centre, until it meets the floor, a side of the box or another grain
     * (contact distance (r + r_j) @p factor); it rests there if that stops
     * it from both sides (the floor, a side, or grains on either side of
     * its centre), else it rolls on over the grain it met; if it rolls past
     * the level of its support's centre it falls (@p drop gives the height
     * at which a disk dropped at a lateral position lands, and the grain it
     * lands on). Returns where it rests.
     */
    template <typename Drop>
    Point<2>
    roll_to_rest(const std::vector<GrainParameters<2>> &grains,
                 Point<2>                               centre,
                 const double                           r,
                 int                                    support,
                 const double                           factor,
                 const Point<2>                        &lower,
                 const Point<2>                        &upper,
                 const Drop                            &drop)
    {
      const double floor      = lower[1] + r;
      const double half_pi    = 0.5 * numbers::PI;
      const double tolerance  = 1e-9;
      double       direction  = 1.;
      bool         has_rolled = false;
      // Each pass ends lower or on a new support; the cap only guards
      // against round-off cycles.
      for (unsigned int pass = 0; pass < 4 * grains.size() + 16; ++pass)
        {
          if (support < 0)
            return centre;
          const Point<2> &a = grains[support].centre;
          const double    R = (r + grains[support].radius) * factor;
          if (!has_rolled)
            direction = (centre[0] >= a[0]) ? 1. : -1.;
          has_rolled = true;
          // The angle from the vertical above the support's centre.
          const double start =
            std::atan2(direction * (centre[0] - a[0]), centre[1] - a[1]);
          double     stop  = half_pi;
          int        event = -2; // -2: falls off, -1: the floor, -3: the side
          const auto consider = [&](const double angle, const int what) {
            if (angle > start + tolerance && angle < stop && stop > start)
              {
                stop  = angle;
                event = what;
              }
          };
          // The floor and the side it rolls towards.
          if (std::abs(floor - a[1]) <= R)
            consider(std::acos((floor - a[1]) / R), -1);
          const double side = direction > 0 ? upper[0] - r : lower[0] + r;
          if (std::abs(side - a[0]) <= R && direction * (side - a[0]) >= 0.)
            consider(std::asin(direction * (side - a[0]) / R), -3);
          // The grains its path around the support meets.
          for (unsigned int j = 0; j < grains.size(); ++j)
            {
              if (static_cast<int>(j) == support)
                continue;
              const Tensor<1, 2> ab = grains[j].centre - a;
              const double       d  = ab.norm();
              const double       Rb = (r + grains[j].radius) * factor;
              if (d > R + Rb || d < std::abs(R - Rb) || !(d > 0.))
                continue;
              const double       l = (R * R - Rb * Rb + d * d) / (2. * d);
              const double       h = std::sqrt(std::max(0., R * R - l * l));
              const Tensor<1, 2> u = ab / d;
              Tensor<1, 2>       v;
              v[0] = -u[1];
              v[1] = u[0];
              for (const double s : {-1., 1.})
                {
                  const Tensor<1, 2> p = l * u + s * h * v;
                  consider(std::atan2(direction * p[0], p[1]),
                           static_cast<int>(j));
                }
              // A grain it touches now and would roll into stops it here.
              const double   ahead = start + 1e-6;
              const Point<2> next(a[0] + direction * R * std::sin(ahead),
                                  a[1] + R * std::cos(ahead));
              if (next.distance(grains[j].centre) < Rb * (1. - tolerance) &&
                  centre.distance(grains[j].centre) < Rb * (1. + 1e-6))
                {
                  stop  = start;
                  event = static_cast<int>(j);
                }
            }
          if (event == -2)
            {
              // Past the side of its support: it falls from there.
              centre[0]  = a[0] + direction * R * (1. + tolerance);
              centre[1]  = drop(centre, r, &support);
              has_rolled = false;
              continue;
            }
          centre[0] = a[0] + direction * R * std::sin(stop);
          centre[1] = a[1] + R * std::cos(stop);
          // The floor or a side holds it (exactly there, not a round-off
          // outside the box).
          if (event == -1)
            centre[1] = floor;
          if (event == -3)
            centre[0] = side;
          if (event < 0)
            return centre;
          const Point<2> &b = grains[event].centre;
          if ((a[0] - centre[0]) * (b[0] - centre[0]) < 0.)
            return centre; // grains on either side
          support = event; // both on one side: roll on over the new one
        }
      return centre;
    }
  } // namespace



  template <int dim>
  std::vector<GrainParameters<dim>>
  random_packing(const RandomPackingParameters<dim> &parameters)
  {
    const Point<dim> &lower    = parameters.lower_corner;
    const Point<dim> &upper    = parameters.upper_corner;
    const double      r_min    = parameters.minimum_radius;
    const double      r_max    = parameters.maximum_radius;
    const double      factor   = 1. + parameters.gap;
    constexpr int     vertical = DepositionColumns<dim>::vertical;

    DepositionColumns<dim>           columns(lower, upper, 2. * r_max * factor);
    const std::vector<unsigned int> &lateral = columns.lateral_directions();

    std::mt19937 generator(parameters.seed);
    const auto   uniform = [&generator](const double a, const double b) {
      return a + (b - a) * ((generator() + 0.5) / 4294967296.);
    };

    std::vector<GrainParameters<dim>> grains;
    const auto                        resting_height =
      [&](const Point<dim> &centre, const double r, int *support) {
        return columns.resting_height(grains, centre, r, factor, support);
      };

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
            int    support = -1;
            double rest    = resting_height(candidate, r, &support);
            if constexpr (dim == 2)
              if (parameters.deposition == "rolling")
                {
                  candidate[vertical] = rest;
                  candidate           = roll_to_rest(grains,
                                           candidate,
                                           r,
                                           support,
                                           factor,
                                           lower,
                                           upper,
                                           resting_height);
                  rest                = candidate[vertical];
                }
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
        columns.add(centre, grains.size());
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
