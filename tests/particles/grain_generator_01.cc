// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// GrainGenerator: the mass of each generated grain (disk, rotated
// rectangle, triangle in 2D; sphere, rotated box in 3D) approaches density
// times the exact area (volume) as the grid is refined; every point lies in
// its grain and its cell, carries mass = density x volume, F = I and the
// initial velocity; GrainInfo (mass, number and mean position of the points)
// agrees with the particles.

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/grain_geometry.h>
#include <grainmpm/particles/material_point_layout.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <iomanip>

#include "../tests.h"

using namespace grainmpm;

template <int dim>
std::string
parameter_text(const unsigned int n_cells)
{
  const std::string n    = std::to_string(n_cells);
  std::string       text = "set Dimension = " + std::to_string(dim) +
                     "\n"
                     "subsection Background grid\n"
                     "  set Lower corner = " +
                     (dim == 2 ? "0, 0" : "0, 0, 0") +
                     "\n"
                     "  set Upper corner = " +
                     (dim == 2 ? "1, 1" : "1, 1, 1") +
                     "\n"
                     "  set Number of cells = " +
                     (dim == 2 ? n + ", " + n : n + ", " + n + ", " + n) +
                     "\n"
                     "end\n"
                     "subsection Materials\n"
                     "  subsection mat\n"
                     "    set Density = 2.5\n"
                     "  end\n"
                     "end\n"
                     "subsection Material points\n"
                     "  set Particles per cell = 2\n"
                     "end\n";
  if (dim == 2)
    text += R"(
subsection Grains
  subsection Grain 1
    set Shape = disk
    set Centre = 0.3, 0.3
    set Radius = 0.2
    set Material = mat
    set Initial velocity = 0.1; -0.2*x
  end
  subsection Grain 2
    set Shape = rectangle
    set Centre = 0.7, 0.7
    set Size = 0.3, 0.15
    set Rotation = 30
    set Material = mat
    set Initial velocity = 0.1; -0.2*x
  end
  subsection Grain 3
    set Shape = polygon
    set Vertices = 0.55, 0.1; 0.95, 0.15; 0.7, 0.45
    set Material = mat
    set Initial velocity = 0.1; -0.2*x
  end
end
)";
  else
    text += R"(
subsection Grains
  subsection Grain 1
    set Shape = sphere
    set Centre = 0.3, 0.3, 0.3
    set Radius = 0.2
    set Material = mat
    set Initial velocity = 0.1; -0.2*x; z
  end
  subsection Grain 2
    set Shape = box
    set Centre = 0.7, 0.7, 0.7
    set Size = 0.33, 0.21, 0.27
    set Rotation = 20
    set Material = mat
    set Initial velocity = 0.1; -0.2*x; z
  end
end
)";
  return text;
}



template <int dim>
void
test(const unsigned int n_cells)
{
  using Layout = MaterialPointLayout<dim>;
  deallog << "dim = " << dim << ", " << n_cells << " cells per direction"
          << std::endl;

  const std::vector<std::string> grain_names =
    (dim == 2 ? std::vector<std::string>{"Grain 1", "Grain 2", "Grain 3"} :
                std::vector<std::string>{"Grain 1", "Grain 2"});
  ParameterHandler prm;
  Parameters<dim>  parameters;
  parameters.declare(prm, {"mat"}, grain_names);
  prm.parse_input_from_string(parameter_text<dim>(n_cells));
  parameters.check();

  BackgroundGrid<dim>             grid(parameters.grid, MPI_COMM_WORLD);
  Particles::ParticleHandler<dim> particle_handler(grid.get_triangulation(),
                                                   grid.get_mapping(),
                                                   Layout::n_properties);
  const auto                      info =
    GrainGenerator<dim>(parameters).generate(grid, particle_handler);

  // Exact areas (volumes).
  std::vector<double> exact;
  if (dim == 2)
    exact = {M_PI * 0.2 * 0.2, 0.3 * 0.15, 0.5 * 0.1325};
  else
    exact = {4. / 3. * M_PI * 0.2 * 0.2 * 0.2, 0.33 * 0.21 * 0.27};
  const double density = 2.5;

  // Sum the particles per grain and check each point.
  const unsigned int                 n_grains = grain_names.size();
  std::vector<double>                mass(n_grains, 0.);
  std::vector<types::particle_index> count(n_grains, 0);
  std::vector<Tensor<1, dim>>        position_sum(n_grains);
  unsigned int                       n_outside = 0;
  double max_position_error = 0., max_property_error = 0.;
  double cell_volume = 1.;
  for (unsigned int d = 0; d < dim; ++d)
    cell_volume *= grid.cell_size()[d];
  for (const auto &particle : particle_handler)
    {
      const auto         properties = particle.get_properties();
      const unsigned int g          = Layout::get_grain(properties);
      const Point<dim>   x          = particle.get_location();
      mass[g] += properties[Layout::mass];
      ++count[g];
      position_sum[g] += x;
      if (!contains(parameters.grains[g], x))
        ++n_outside;
      const auto cell = particle.get_surrounding_cell();
      for (unsigned int d = 0; d < dim; ++d)
        max_position_error =
          std::max(max_position_error,
                   std::abs(cell->vertex(0)[d] +
                            grid.cell_size()[d] *
                              particle.get_reference_location()[d] -
                            x[d]));
      // Volume = cell volume / 2^dim, mass = density x volume, F = I,
      // v = (0.1, -0.2 x (, z)).
      const double volume = cell_volume / (1U << dim);
      double       error =
        std::abs(properties[Layout::volume] / volume - 1.) +
        std::abs(properties[Layout::initial_volume] / volume - 1.) +
        std::abs(properties[Layout::mass] / (density * volume) - 1.);
      Tensor<1, dim> velocity;
      velocity[0] = 0.1;
      velocity[1] = -0.2 * x[0];
      if (dim == 3)
        velocity[dim - 1] = x[dim - 1];
      error += (Layout::get_velocity(properties) - velocity).norm();
      error += (Layout::get_deformation_gradient(properties) -
                unit_symmetric_tensor<dim>())
                 .norm();
      error += Layout::get_stress(properties).norm();
      max_property_error = std::max(max_property_error, error);
    }

  for (unsigned int g = 0; g < n_grains; ++g)
    {
      const double relative_error = mass[g] / (density * exact[g]) - 1.;
      deallog << parameters.grains[g].shape_text << ": " << count[g]
              << " points, mass / (density x exact "
              << (dim == 2 ? "area" : "volume")
              << ") - 1 = " << std::setprecision(3) << relative_error
              << std::setprecision(6) << std::endl;
      deallog << "  GrainInfo: mass / particle sum = " << info[g].mass / mass[g]
              << ", points " << info[g].n_particles
              << (info[g].n_particles == count[g] ? " (same)" : " (different)")
              << ", centroid "
              << ((info[g].centroid - position_sum[g] / count[g]).norm() <
                      1e-12 ?
                    "the points' mean" :
                    "not the points' mean")
              << std::endl;
    }
  deallog << "points outside their grain: " << n_outside
          << ", max |x - (X_0 + h xi)| / h = "
          << filter_out_small_numbers(max_position_error /
                                      grid.minimum_cell_size())
          << ", max property error = "
          << filter_out_small_numbers(max_property_error) << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>(20);
  test<2>(80);
  test<3>(10);
  test<3>(30);
}
