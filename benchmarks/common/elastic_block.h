// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The set-up shared by the benchmarks: a block of elastic material
// (E = 1000, nu = 0.3, rho = 1, plane strain) filling [0.25, 0.75]^2 of an
// n x n grid with p x p points per cell, and its grid, particles,
// materials and grains.

#ifndef grainmpm_benchmarks_elastic_block_h
#define grainmpm_benchmarks_elastic_block_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/material_point_layout.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace grainmpm::benchmarks
{
  struct ElasticBlock
  {
    static constexpr double youngs_modulus = 1000.;
    static constexpr double poissons_ratio = 0.3;
    static constexpr double density        = 1.;
    static constexpr double lambda =
      youngs_modulus * poissons_ratio /
      ((1 + poissons_ratio) * (1 - 2 * poissons_ratio));
    static constexpr double mu = youngs_modulus / (2 * (1 + poissons_ratio));

    /** The dilatational wave speed. */
    static double
    wave_speed()
    {
      return std::sqrt((lambda + 2 * mu) / density);
    }

    /**
     * The block on @p n_cells^2 cells with @p per_direction^2 points per
     * cell, initial velocity @p velocity (';'-separated expressions), time
     * step @p dt, and @p extra parameter text (other subsections).
     */
    ElasticBlock(const unsigned int n_cells,
                 const unsigned int per_direction,
                 const std::string &velocity,
                 const double       dt,
                 const std::string &extra = "")
    {
      std::ostringstream text;
      text << "set Dimension = 2\n"
           << "subsection Background grid\n  set Number of cells = " << n_cells
           << ", " << n_cells << "\nend\n"
           << "subsection Materials\n  subsection block\n    set Density = "
           << density << "\n    set Young's modulus = " << youngs_modulus
           << "\n    set Poisson's ratio = " << poissons_ratio
           << "\n  end\nend\n"
           << "subsection Grains\n  subsection Grain 1\n    set Shape = "
              "rectangle\n    set Centre = 0.5, 0.5\n    set Size = 0.5, 0.5\n"
           << "    set Material = block\n    set Initial velocity = "
           << velocity << "\n  end\nend\n"
           << "subsection Material points\n  set Particles per cell = "
           << per_direction << "\nend\n"
           << extra << "subsection Time stepping\n  set Time step = " << dt
           << "\nend\n";
      ParameterHandler prm;
      parameters.declare(prm, {"block"}, {"Grain 1"});
      prm.parse_input_from_string(text.str());
      parameters.check();

      grid =
        std::make_unique<BackgroundGrid<2>>(parameters.grid, MPI_COMM_WORLD);
      particle_handler = std::make_unique<Particles::ParticleHandler<2>>(
        grid->get_triangulation(),
        grid->get_mapping(),
        MaterialPointLayout<2>::n_properties);
      materials.emplace_back(
        create_constitutive_model<2>(parameters.materials[0],
                                     parameters.physics.two_dimensional_model));
      grains = GrainGenerator<2>(parameters).generate(*grid, *particle_handler);
    }

    /**
     * Move the points by a quarter of their spacing in each direction: off
     * the regular arrangement, whose GIMP boxes tile the cells exactly, one
     * point per cell and axis touches 3 nodes along it, as on time average
     * in a flow (2 + 1 / points per direction nodes per axis).
     */
    void
    move_off_arrangement()
    {
      const Tensor<1, 2> &h = grid->cell_size();
      const double        fraction =
        0.25 / parameters.material_points.particles_per_cell;
      for (auto &particle : *particle_handler)
        {
          Point<2> x         = particle.get_location();
          Point<2> reference = particle.get_reference_location();
          for (unsigned int d = 0; d < 2; ++d)
            {
              x[d] += fraction * h[d];
              reference[d] += fraction;
            }
          particle.set_location(x);
          particle.set_reference_location(reference);
        }
    }

    Parameters<2>                                      parameters;
    std::unique_ptr<BackgroundGrid<2>>                 grid;
    std::unique_ptr<Particles::ParticleHandler<2>>     particle_handler;
    std::vector<std::unique_ptr<ConstitutiveModel<2>>> materials;
    std::vector<GrainInfo<2>>                          grains;
  };
} // namespace grainmpm::benchmarks

#endif
