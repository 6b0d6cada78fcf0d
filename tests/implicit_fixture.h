// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A whole implicit set-up (parameters, grid, grains, materials, particles
// and the ImplicitTheta stepper) read from a parameter text, for the
// tests of the implicit scheme. The tests choose their steps themselves, so
// unless the text says otherwise the steps are not grown (Time
// stepping/Maximum CFL number = 0): no step is rejected for the energy it
// creates, which only grown steps are.

#ifndef grainmpm_tests_implicit_fixture_h
#define grainmpm_tests_implicit_fixture_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/implicit_theta.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/mpi.h>

#include <fstream>
#include <memory>
#include <string>

namespace grainmpm
{
  template <int dim>
  struct ImplicitFixture
  {
    explicit ImplicitFixture(const std::string &text, const std::string &name)
    {
      const std::string file = name + ".prm";
      // Written by one rank, read by all.
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          std::ofstream out(file);
          out << text;
          if (text.find("Maximum CFL number") == std::string::npos)
            out << "\nsubsection Time stepping\n"
                << "  set Maximum CFL number = 0\nend\n";
        }
      const int ierr = MPI_Barrier(MPI_COMM_WORLD);
      AssertThrowMPI(ierr);
      parameters.parse(file, prm);
      grid =
        std::make_unique<BackgroundGrid<dim>>(parameters.grid, MPI_COMM_WORLD);
      particle_handler = std::make_unique<Particles::ParticleHandler<dim>>(
        grid->get_triangulation(),
        grid->get_mapping(),
        MaterialPointLayout<dim>::n_properties);
      for (const auto &material : parameters.materials)
        materials.emplace_back(create_constitutive_model<dim>(
          material, parameters.physics.two_dimensional_model));
      GrainGenerator<dim> generator(parameters);
      grains  = generator.generate(*grid, *particle_handler);
      stepper = std::make_unique<ImplicitTheta<dim>>(parameters,
                                                     *grid,
                                                     grains,
                                                     materials);
    }

    ParameterHandler                                     prm;
    Parameters<dim>                                      parameters;
    std::unique_ptr<BackgroundGrid<dim>>                 grid;
    std::unique_ptr<Particles::ParticleHandler<dim>>     particle_handler;
    std::vector<std::unique_ptr<ConstitutiveModel<dim>>> materials;
    std::vector<GrainInfo<dim>>                          grains;
    std::unique_ptr<ImplicitTheta<dim>>                  stepper;
  };



  /**
   * The exact stiffness action f = K z of small-strain isotropic
   * elasticity (plane strain in 2D) with Lame constants @p lambda, @p mu,
   * assembled independently of ThetaResidual from the particle volumes of
   * @p particle_handler and the slots of @p cache: f_s = sum_p V_p
   * sigma(eps(z)) . grad S_sp, eps = sym sum_s z_s (x) grad S_sp.
   */
  template <int dim>
  void
  stiffness_action(const BackgroundGrid<dim>             &grid,
                   const Particles::ParticleHandler<dim> &particle_handler,
                   const TransferCache<dim>              &cache,
                   const double                           lambda,
                   const double                           mu,
                   const LinearAlgebra::distributed::Vector<double> &z,
                   LinearAlgebra::distributed::Vector<double>       &f)
  {
    f.reinit(z, true);
    f             = 0.;
    std::size_t p = 0;
    for_each_particle(
      grid, particle_handler, [&](const auto &, const auto &particle) {
        const double volume =
          particle->get_properties()[MaterialPointLayout<dim>::volume];
        SymmetricTensor<2, dim> strain;
        for (unsigned int v = cache.first_entry[p];
             v < cache.first_entry[p + 1];
             ++v)
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              strain[i][j] += 0.5 * (z.local_element(cache.slots[v] * dim + i) *
                                       cache.shape_gradients[v][j] +
                                     z.local_element(cache.slots[v] * dim + j) *
                                       cache.shape_gradients[v][i]);
        const SymmetricTensor<2, dim> stress =
          lambda * trace(strain) * unit_symmetric_tensor<dim>() +
          2. * mu * strain;
        for (unsigned int v = cache.first_entry[p];
             v < cache.first_entry[p + 1];
             ++v)
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              f.local_element(cache.slots[v] * dim + i) +=
                volume * stress[i][j] * cache.shape_gradients[v][j];
        ++p;
      });
  }
} // namespace grainmpm

#endif
