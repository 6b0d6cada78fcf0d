// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// TransferCache with uGIMP and cpGIMP weights on an anisotropic box:
// - the values of every particle sum to one and the gradients to zero,
//   also for particles whose box is cut by a face of the grid box;
// - away from the box faces each value is the product of the closed-form
//   1D uGIMP factors of Bardenhagen & Kober (2004), written out here
//   independently of the code's integral-of-the-hat form, and the number
//   of nodes per particle is 2 or 3 per axis as the formula says;
// - the gradients match central differences of the values (node by node),
//   also across the breakpoints of the piecewise formula;
// - cpGIMP with a pure rotation as deformation gradient gives the uGIMP
//   weights, and with a stretch the closed form with the stretched box.

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/particles/particle_handler.h>

#include <map>

#include "../tests.h"

#include "anisotropic_box.h"

using namespace grainmpm;

// The 1D uGIMP factor for a node at distance r = x - x_i, cell size h,
// half-width l (Bardenhagen & Kober 2004, eq. for the linear hats).
double
closed_form(const double r_signed, const double h, const double l)
{
  const double r = std::abs(r_signed);
  if (r < l)
    return 1. - (r * r + l * l) / (2. * h * l);
  if (r < h - l)
    return 1. - r / h;
  if (r < h + l)
    return (h + l - r) * (h + l - r) / (4. * h * l);
  return 0.;
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  using Layout = MaterialPointLayout<dim>;

  // An anisotropic box with unequal cells: h = (0.5, 0.5, 0.25).
  const BackgroundGridParameters<dim> parameters =
    anisotropic_box_parameters<dim>();
  BackgroundGrid<dim>   grid(parameters, MPI_COMM_WORLD);
  const Tensor<1, dim> &h = grid.cell_size();
  Tensor<1, dim>        half_width;
  for (unsigned int d = 0; d < dim; ++d)
    half_width[d] = h[d] / 4.; // 2 points per cell and direction

  // Positions: generic interior ones, then ones whose box is cut by the
  // lower or upper face, then a finite-difference stencil around a point
  // 0.3 l from a cell face (where the formula changes piece).
  std::vector<Point<dim>> positions =
    spread_positions(parameters, 6, 0.15, 0.13, 0.041);
  const unsigned int n_interior = positions.size();
  for (unsigned int d = 0; d < dim; ++d)
    for (const double offset : {0., 0.1, 0.2})
      {
        Point<dim> lower = positions[d];
        lower[d]         = parameters.lower_corner[d] + offset * h[d];
        positions.push_back(lower);
        Point<dim> upper = positions[d + 1];
        upper[d]         = parameters.upper_corner[d] - offset * h[d];
        positions.push_back(upper);
      }
  const unsigned int n_plain = positions.size();
  Point<dim>         x0;
  for (unsigned int d = 0; d < dim; ++d)
    x0[d] = parameters.lower_corner[d] + (2. + (0.3 - 0.1 * d) * 0.25) * h[d];
  const double eps = 1e-5 * grid.minimum_cell_size();
  add_difference_stencil(positions, x0, eps);

  // Deformation gradients for cpGIMP: a rotation by 0.7 rad in the x-y
  // plane, and a stretch diag(1.4, 0.8, 1.2).
  Tensor<2, dim> rotation = unit_symmetric_tensor<dim>();
  rotation[0][0] = rotation[1][1] = std::cos(0.7);
  rotation[0][1]                  = -std::sin(0.7);
  rotation[1][0]                  = std::sin(0.7);
  Tensor<2, dim> stretch;
  for (unsigned int d = 0; d < dim; ++d)
    stretch[d][d] = (d == 0 ? 1.4 : (d == 1 ? 0.8 : 1.2));

  for (const ShapeFunctions kernel :
       {ShapeFunctions::ugimp, ShapeFunctions::cpgimp})
    for (const Tensor<2, dim> &F : {rotation, stretch})
      {
        if (kernel == ShapeFunctions::ugimp && F == stretch)
          continue;
        Particles::ParticleHandler<dim> particle_handler(
          grid.get_triangulation(), grid.get_mapping(), Layout::n_properties);
        for (unsigned int i = 0; i < positions.size(); ++i)
          {
            const auto cell_and_reference =
              GridTools::find_active_cell_around_point(grid.get_mapping(),
                                                       grid.get_triangulation(),
                                                       positions[i]);
            std::vector<double> properties(Layout::n_properties, 0.);
            properties[Layout::mass] = 1.;
            Layout::set_deformation_gradient(F, make_array_view(properties));
            particle_handler.insert_particle(positions[i],
                                             cell_and_reference.second,
                                             i,
                                             cell_and_reference.first,
                                             make_array_view(properties));
          }
        particle_handler.update_cached_numbers();
        TransferCache<dim> cache;
        cache.reinit(grid, particle_handler, {0}, kernel, half_width);

        // The box the closed form should see.
        Tensor<1, dim> width = half_width;
        if (kernel == ShapeFunctions::cpgimp)
          for (unsigned int d = 0; d < dim; ++d)
            width[d] *= F[d].norm();

        std::vector<unsigned int> p_of_id(positions.size());
        {
          unsigned int p = 0;
          for_each_particle(grid,
                            particle_handler,
                            [&](const auto &, const auto &particle) {
                              p_of_id[particle->get_id()] = p++;
                            });
        }
        const auto weights = [&](const unsigned int i) {
          std::map<unsigned int, std::pair<double, Tensor<1, dim>>> w;
          const unsigned int p = p_of_id[i];
          for (unsigned int e = cache.first_entry[p];
               e < cache.first_entry[p + 1];
               ++e)
            w[cache.nodes[e]] = {cache.shape_values[e],
                                 cache.shape_gradients[e]};
          return w;
        };

        double       max_sum_error = 0., max_gradient_sum = 0.;
        double       max_formula_error = 0.;
        unsigned int min_entries = 100, max_entries = 0, count_errors = 0;
        for (unsigned int i = 0; i < n_plain; ++i)
          {
            double         sum = 0.;
            Tensor<1, dim> gradient_sum;
            const auto     w = weights(i);
            for (const auto &[node, value] : w)
              {
                sum += value.first;
                gradient_sum += value.second;
                if (i < n_interior)
                  {
                    double formula = 1.;
                    for (unsigned int d = 0; d < dim; ++d)
                      formula *= closed_form(positions[i][d] -
                                               grid.node_position(node)[d],
                                             h[d],
                                             width[d]);
                    max_formula_error =
                      std::max(max_formula_error,
                               std::abs(value.first - formula));
                  }
              }
            max_sum_error = std::max(max_sum_error, std::abs(sum - 1.));
            max_gradient_sum =
              std::max(max_gradient_sum,
                       gradient_sum.norm() * grid.minimum_cell_size());
            if (i < n_interior)
              {
                // Nodes per axis: 3 if the box reaches over a cell face
                // (distance to the nearest face below the half-width).
                unsigned int expected = 1;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double s =
                      (positions[i][d] - parameters.lower_corner[d]) / h[d];
                    const double to_face = std::abs(s - std::round(s));
                    expected *= (to_face < width[d] / h[d] ? 3 : 2);
                  }
                if (w.size() != expected)
                  ++count_errors;
                min_entries = std::min<unsigned int>(min_entries, w.size());
                max_entries = std::max<unsigned int>(max_entries, w.size());
              }
          }

        // Gradients against central differences, node by node.
        const auto   centre    = weights(n_plain);
        double       max_error = 0., gradient_scale = 0.;
        unsigned int n_missing = 0;
        for (const auto &[node, value] : centre)
          {
            Tensor<1, dim> difference_quotient;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const auto minus = weights(n_plain + 1 + 2 * d);
                const auto plus  = weights(n_plain + 2 + 2 * d);
                if (minus.count(node) == 0 || plus.count(node) == 0)
                  {
                    ++n_missing;
                    continue;
                  }
                difference_quotient[d] =
                  (plus.at(node).first - minus.at(node).first) / (2. * eps);
              }
            max_error =
              std::max(max_error, (difference_quotient - value.second).norm());
            gradient_scale = std::max(gradient_scale, value.second.norm());
          }

        deallog << (kernel == ShapeFunctions::ugimp ? "uGIMP" : "cpGIMP")
                << (F == rotation ? ", F = rotation" : ", F = stretch")
                << ": max |sum S - 1| = "
                << filter_out_small_numbers(max_sum_error)
                << ", max |sum grad S| h = "
                << filter_out_small_numbers(max_gradient_sum) << std::endl;
        deallog << "  interior: max |S - closed form| = "
                << filter_out_small_numbers(max_formula_error)
                << ", nodes per particle " << min_entries << " to "
                << max_entries << ", wrong node counts " << count_errors
                << std::endl;
        deallog << "  max |grad S - FD(S)| / max |grad S| = "
                << filter_out_small_numbers(max_error / gradient_scale, 1e-8)
                << " over " << centre.size() << " nodes, " << n_missing
                << " missing" << std::endl;
      }
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
