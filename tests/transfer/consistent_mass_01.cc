// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// MassMatrix, the matrix-free consistent mass matrix M_C = P2G of G2P
// (consistent fraction 1) and its blend with the lumped mass, on two
// touching grains with linear and uGIMP shape functions, points moved off
// their regular arrangement, on 1 and 2 ranks:
// - its row sums are the lumped masses: M_C 1 = m;
// - it is symmetric: u . M_C w = w . M_C u;
// - it lies between zero and the lumped mass: 0 < v . M_C v <= v . M_L v
//   (Jensen's inequality per particle), near the lumped mass for a smooth
//   field and far below it for the checkerboard mode of the grid;
// - the blend M = 0.1 M_L + 0.9 M_C: MassMatrix::solve inverts vmult, and
//   the kinetic energy is 1/2 u.M u.

#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer.h>

#include "../tests.h"

using namespace grainmpm;
using VectorType = LinearAlgebra::distributed::Vector<double>;

void
check(const std::string &kernel)
{
  const std::string text = R"(
set Dimension = 2
subsection Background grid
  set Number of cells = 16, 16
end
subsection Materials
  subsection elastic
    set Density = 2
  end
end
subsection Grains
  subsection Grain 1
    set Shape    = disk
    set Centre   = 0.31, 0.5
    set Radius   = 0.2
    set Material = elastic
  end
  subsection Grain 2
    set Shape    = rectangle
    set Centre   = 0.7, 0.45
    set Size     = 0.18, 0.5
    set Material = elastic
  end
end
subsection Material points
  set Shape functions = )" +
                           kernel + R"(
end
)";
  Parameters<2>    parameters;
  ParameterHandler prm;
  parameters.declare(prm, {"elastic"}, {"Grain 1", "Grain 2"});
  prm.parse_input_from_string(text);
  parameters.check();
  BackgroundGrid<2>             grid(parameters.grid, MPI_COMM_WORLD);
  Particles::ParticleHandler<2> particle_handler(
    grid.get_triangulation(),
    grid.get_mapping(),
    MaterialPointLayout<2>::n_properties);
  std::vector<std::unique_ptr<ConstitutiveModel<2>>> materials;
  materials.emplace_back(
    create_constitutive_model<2>(parameters.materials[0],
                                 parameters.physics.two_dimensional_model));
  const std::vector<GrainInfo<2>> grains =
    GrainGenerator<2>(parameters).generate(grid, particle_handler);

  // Off the regular arrangement, within the cells: a shift that depends on
  // the position only (the same on any number of ranks).
  const double h = grid.minimum_cell_size();
  for (auto &particle : particle_handler)
    {
      const Point<2> x = particle.get_location();
      Tensor<1, 2>   shift;
      shift[0] = 0.1 * h * std::sin(37. * x[0] + 11. * x[1]);
      shift[1] = 0.1 * h * std::cos(23. * x[0] - 7. * x[1]);
      particle.set_location(x + shift);
      particle.set_reference_location(particle.get_reference_location() +
                                      shift / h);
    }

  Transfer<2> transfer(parameters, grid, grains, materials);
  transfer.reinit(particle_handler);
  const GrainFieldLayout<2> &layout = transfer.get_layout();
  VectorType                 masses, momenta, gradients;
  transfer.particles_to_grid(particle_handler, &masses, momenta, &gradients);

  // Vectors: ones, and two smooth fields that differ between the grains.
  VectorType ones, u, w, checkerboard;
  layout.reinit_vector(ones, 2);
  layout.reinit_vector(u, 2);
  layout.reinit_vector(w, 2);
  layout.reinit_vector(checkerboard, 2);
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    {
      const Point<2>    &x     = grid.node_position(layout.node(s));
      const unsigned int field = layout.field(s);
      for (unsigned int d = 0; d < 2; ++d)
        {
          ones.local_element(2 * s + d) = 1.;
          u.local_element(2 * s + d) =
            std::sin(3.1 * x[0] + 1.7 * x[1] + d + 2. * field);
          w.local_element(2 * s + d) =
            std::cos(2.3 * x[0] - 4.1 * x[1] + 3. * d - field);
          checkerboard.local_element(2 * s + d) =
            (std::lround(x[0] / h) + std::lround(x[1] / h)) % 2 == 0 ? 1. : -1.;
        }
    }

  MassMatrix<2> consistent;
  consistent.reinit(transfer, particle_handler, masses, 1.);
  VectorType M_ones, M_u, M_w, M_checkerboard;
  for (VectorType *v : {&M_ones, &M_u, &M_w, &M_checkerboard})
    layout.reinit_vector(*v, 2);
  consistent.vmult(M_checkerboard, checkerboard);
  consistent.vmult(M_ones, ones);
  consistent.vmult(M_u, u);
  consistent.vmult(M_w, w);

  double row_sum_error = 0., largest_mass = 0., lumped_u = 0.,
         lumped_checkerboard = 0.;
  for (unsigned int s = 0; s < layout.n_slots(); ++s)
    {
      largest_mass = std::max(largest_mass, masses.local_element(s));
      for (unsigned int d = 0; d < 2; ++d)
        {
          row_sum_error = std::max(row_sum_error,
                                   std::abs(M_ones.local_element(2 * s + d) -
                                            masses.local_element(s)));
          lumped_u += masses.local_element(s) * u.local_element(2 * s + d) *
                      u.local_element(2 * s + d);
          lumped_checkerboard += masses.local_element(s);
        }
    }
  const MPI_Comm communicator = MPI_COMM_WORLD;
  row_sum_error       = Utilities::MPI::max(row_sum_error, communicator);
  largest_mass        = Utilities::MPI::max(largest_mass, communicator);
  lumped_u            = Utilities::MPI::sum(lumped_u, communicator);
  lumped_checkerboard = Utilities::MPI::sum(lumped_checkerboard, communicator);
  const double checkerboard_ratio =
    (checkerboard * M_checkerboard) / lumped_checkerboard;
  const double asymmetry =
    std::abs((u * M_w) - (w * M_u)) / (u.l2_norm() * M_w.l2_norm());
  const double consistent_u = u * M_u;

  deallog << kernel << ": max |M_C 1 - m| / max m < 1e-14: "
          << (row_sum_error / largest_mass < 1e-14 ? "yes" : "no")
          << ", symmetric to 1e-14: " << (asymmetry < 1e-14 ? "yes" : "no")
          << ", 0 < u.M_C u <= u.M_L u: "
          << (consistent_u > 0. && consistent_u <= lumped_u ? "yes" : "no")
          << " (ratio " << std::fixed << std::setprecision(3)
          << consistent_u / lumped_u << "), checkerboard ratio "
          << checkerboard_ratio
          << " < 0.5: " << (checkerboard_ratio < 0.5 ? "yes" : "no")
          << std::defaultfloat << std::endl;

  // The blend: solve M x = M u and compare with u; 1/2 u.M u.
  MassMatrix<2> blended;
  blended.reinit(transfer, particle_handler, masses, 0.9);
  VectorType M_blend_u, x;
  layout.reinit_vector(M_blend_u, 2);
  blended.vmult(M_blend_u, u);
  const unsigned int iterations = blended.solve(M_blend_u, x);
  x -= u;
  const double energy =
    Utilities::MPI::sum(blended.local_kinetic_energy(u), communicator);
  deallog << kernel << ": blend 0.9: solve M x = M u to |x - u| / |u| < 1e-9: "
          << (x.l2_norm() / u.l2_norm() < 1e-9 ? "yes" : "no")
          << " in at most 40 CG iterations: "
          << (iterations <= 40 ? "yes" : "no")
          << ", 1/2 u.M u = 1/2 (0.1 u.M_L u + 0.9 u.M_C u): "
          << (std::abs(energy - 0.5 * (0.1 * lumped_u + 0.9 * consistent_u)) <
                  1e-13 * lumped_u ?
                "yes" :
                "no")
          << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();
  check("linear");
  check("uGIMP");
}
