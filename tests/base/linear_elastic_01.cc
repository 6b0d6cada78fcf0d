// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// LinearElastic: a uniaxial strain increment gives sigma_xx = (lambda + 2
// mu) eps, sigma_yy = lambda eps (plane strain and 3D: sigma_zz = lambda
// eps; plane stress: sigma_zz = 0 and E / (1 - nu^2)); a rotation increment
// rotates the stress (Jaumann) and keeps its invariants to first order; the
// strain energy density is sigma^2 / (2E) in uniaxial stress, tau^2 / (2 mu)
// in shear and 1/2 sigma : eps after a strain increment; the wave speed.

#include <grainmpm/materials/linear_elastic.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

template <int dim>
void
test(const TwoDimensionalModel model)
{
  const bool plane_stress =
    (dim == 2 && model == TwoDimensionalModel::plane_stress);
  deallog << "dim = " << dim
          << (dim == 3     ? "" :
              plane_stress ? ", plane stress" :
                             ", plane strain")
          << std::endl;

  const double             rho = 1200., E = 2.5e6, nu = 0.3;
  const LinearElastic<dim> material(rho, E, nu, model);
  const double             mu      = E / (2. * (1. + nu));
  const double             lambda  = E * nu / ((1. + nu) * (1. - 2. * nu));
  double                   history = 0.;

  // Uniaxial strain increment from zero stress.
  const double   eps = 1e-3;
  Tensor<2, dim> increment;
  increment[0][0] = eps;
  const SymmetricTensor<2, 3> sigma =
    material.update_stress(SymmetricTensor<2, 3>(), increment, history);
  if (plane_stress)
    {
      const double modulus = E / (1. - nu * nu);
      deallog << "sigma_xx / (E/(1-nu^2) eps) = "
              << sigma[0][0] / (modulus * eps)
              << ", sigma_yy / (nu E/(1-nu^2) eps) = "
              << sigma[1][1] / (nu * modulus * eps)
              << ", sigma_zz / sigma_xx = "
              << filter_out_small_numbers(sigma[2][2] / sigma[0][0])
              << std::endl;
    }
  else
    deallog << "sigma_xx / ((lambda+2mu) eps) = "
            << sigma[0][0] / ((lambda + 2. * mu) * eps)
            << ", sigma_yy / (lambda eps) = " << sigma[1][1] / (lambda * eps)
            << ", sigma_zz / (lambda eps) = " << sigma[2][2] / (lambda * eps)
            << std::endl;
  deallog << "shear components / sigma_xx = "
          << filter_out_small_numbers((std::abs(sigma[0][1]) +
                                       std::abs(sigma[0][2]) +
                                       std::abs(sigma[1][2])) /
                                      sigma[0][0])
          << std::endl;
  // The stored energy is the work 1/2 sigma : eps of the increment.
  deallog << "energy / (1/2 sigma_xx eps) = "
          << material.strain_energy_density(sigma) / (0.5 * sigma[0][0] * eps)
          << std::endl;

  // Energy of a uniaxial stress and of a pure shear stress.
  SymmetricTensor<2, 3> uniaxial, shear;
  uniaxial[1][1] = 7.;
  shear[0][1]    = 3.;
  deallog << "energy of uniaxial stress / (sigma^2 / 2E) = "
          << material.strain_energy_density(uniaxial) / (49. / (2. * E))
          << ", of shear stress / (tau^2 / 2mu) = "
          << material.strain_energy_density(shear) / (9. / (2. * mu))
          << std::endl;

  // A small rotation increment about z: R = I + W, W = theta (e_y e_x^T -
  // e_x e_y^T) (counter-clockwise).
  SymmetricTensor<2, 3> sigma0;
  sigma0[0][0] = 1.;
  sigma0[1][1] = -0.5;
  sigma0[2][2] = 0.3;
  sigma0[0][1] = 0.2;
  if (dim == 3)
    sigma0[1][2] = -0.4;
  for (const double theta : {1e-3, 1e-4})
    {
      Tensor<2, dim> rotation;
      rotation[0][1] = -theta;
      rotation[1][0] = theta;
      const SymmetricTensor<2, 3> rotated =
        material.update_stress(sigma0, rotation, history);
      Tensor<2, 3> R = unit_symmetric_tensor<3>();
      R[0][1]        = -std::sin(theta);
      R[1][0]        = std::sin(theta);
      R[0][0] = R[1][1] = std::cos(theta);
      const Tensor<2, 3> exact =
        R * static_cast<Tensor<2, 3>>(sigma0) * transpose(R);
      deallog << "theta = " << theta
              << ": change of sigma_xy / change of (R sigma R^T)_xy = "
              << (rotated[0][1] - sigma0[0][1]) / (exact[0][1] - sigma0[0][1])
              << std::endl;
      deallog << "  |sigma' - R sigma R^T| / (theta |sigma|) = "
              << (static_cast<Tensor<2, 3>>(rotated) - exact).norm() /
                   (theta * sigma0.norm())
              << ", change of trace / |sigma| = "
              << filter_out_small_numbers((trace(rotated) - trace(sigma0)) /
                                          sigma0.norm())
              << ", change of |sigma| / (theta |sigma|) = "
              << (rotated.norm() - sigma0.norm()) / (theta * sigma0.norm())
              << std::endl;
    }

  const double expected_speed = plane_stress ?
                                  std::sqrt(E / (rho * (1. - nu * nu))) :
                                  std::sqrt((lambda + 2. * mu) / rho);
  deallog << "wave speed / expected = "
          << material.wave_speed() / expected_speed
          << ", density = " << material.density() / rho << " rho" << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>(TwoDimensionalModel::plane_strain);
  test<2>(TwoDimensionalModel::plane_stress);
  test<3>(TwoDimensionalModel::plane_strain);
}
