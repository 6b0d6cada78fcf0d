// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/materials/constitutive_model_factory.h>
#include <grainmpm/materials/linear_elastic.h>

#include <cmath>

namespace grainmpm
{
  template <int dim>
  LinearElastic<dim>::LinearElastic(const double              density,
                                    const double              youngs_modulus,
                                    const double              poissons_ratio,
                                    const TwoDimensionalModel model)
    : mass_density(density)
    , youngs_modulus(youngs_modulus)
    , poissons_ratio(poissons_ratio)
    , plane_stress(dim == 2 && model == TwoDimensionalModel::plane_stress)
  {
    mu     = youngs_modulus / (2. * (1. + poissons_ratio));
    lambda = youngs_modulus * poissons_ratio /
             ((1. + poissons_ratio) * (1. - 2. * poissons_ratio));
    if (plane_stress)
      {
        // Eliminating de_zz from sigma_zz = 0 gives the plane-stress
        // modulus lambda* = 2 mu lambda / (lambda + 2 mu), and the wave speed
        // sqrt(E / (rho (1 - nu^2))).
        lambda = 2. * mu * lambda / (lambda + 2. * mu);
      }
    dilatational_wave_speed = std::sqrt((lambda + 2. * mu) / density);
  }



  template <int dim>
  LinearElastic<dim>::LinearElastic(const MaterialParameters &material,
                                    const TwoDimensionalModel model)
    : LinearElastic(material.density,
                    material.youngs_modulus,
                    material.poissons_ratio,
                    model)
  {}



  template <int dim>
  SymmetricTensor<2, 3>
  LinearElastic<dim>::update_stress(
    const SymmetricTensor<2, 3> &stress,
    const Tensor<2, dim>        &displacement_gradient_increment,
    double & /*plastic_strain*/) const
  {
    // Written out component by component (it runs once per particle and
    // residual evaluation of the implicit solver): the strain increment
    // sym(dt grad v) and the spin increment skw(dt grad v) live in the
    // first dim rows and columns; in 2D the out-of-plane ones are zero.
    const Tensor<2, dim> &L = displacement_gradient_increment;
    if constexpr (dim == 2)
      {
        // The general code below written out for 2D, in the same order of
        // operations and without the zero diagonal of the spin (the same
        // results); the implicit residual calls this once per particle and
        // evaluation.
        const double w01        = 0.5 * (L[0][1] - L[1][0]);
        const double w10        = 0.5 * (L[1][0] - L[0][1]);
        const double s00        = stress.access_raw_entry(0);
        const double s11        = stress.access_raw_entry(1);
        const double s22        = stress.access_raw_entry(2);
        const double s01        = stress.access_raw_entry(3);
        const double s02        = stress.access_raw_entry(4);
        const double s12        = stress.access_raw_entry(5);
        double       r00        = s00 + w01 * s01 - s01 * w10;
        double       r01        = s01 + w01 * s11 - s00 * w01;
        double       r11        = s11 + w10 * s01 - s01 * w01;
        const double r02        = s02 + w01 * s12;
        const double r12        = s12 + w10 * s02;
        double       r22        = s22;
        const double volumetric = L[0][0] + L[1][1];
        r00 += 2. * mu * L[0][0] + lambda * volumetric;
        r01 += mu * (L[0][1] + L[1][0]);
        r11 += 2. * mu * L[1][1] + lambda * volumetric;
        if (!plane_stress)
          r22 += lambda * volumetric;
        SymmetricTensor<2, 3> new_stress;
        new_stress.access_raw_entry(0) = r00;
        new_stress.access_raw_entry(1) = r11;
        new_stress.access_raw_entry(2) = r22;
        new_stress.access_raw_entry(3) = r01;
        new_stress.access_raw_entry(4) = r02;
        new_stress.access_raw_entry(5) = r12;
        return new_stress;
      }
    double spin[dim][dim];
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int k = 0; k < dim; ++k)
        spin[i][k] = 0.5 * (L[i][k] - L[k][i]);

    // Jaumann rotation of the old stress: sigma + dW sigma - sigma dW, on
    // plain arrays (SymmetricTensor's [i][j] accessors are slow here).
    double old_stress[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        old_stress[i][j] = old_stress[j][i] = stress.access_raw_entry(
          SymmetricTensor<2, 3>::component_to_unrolled_index(
            TableIndices<2>(i, j)));
    double rotated[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        {
          double value = old_stress[i][j];
          for (unsigned int k = 0; k < dim; ++k)
            {
              if (i < dim)
                value += spin[i][k] * old_stress[k][j];
              if (j < dim)
                value -= old_stress[i][k] * spin[k][j];
            }
          rotated[i][j] = value;
        }

    // The in-plane trace; in plane stress lambda is already the reduced one
    // and sigma_zz gets no increment.
    double volumetric = 0.;
    for (unsigned int i = 0; i < dim; ++i)
      volumetric += L[i][i];
    for (unsigned int i = 0; i < dim; ++i)
      {
        rotated[i][i] += 2. * mu * L[i][i] + lambda * volumetric;
        for (unsigned int j = i + 1; j < dim; ++j)
          rotated[i][j] += mu * (L[i][j] + L[j][i]);
      }
    if (dim == 2 && !plane_stress)
      rotated[2][2] += lambda * volumetric;

    SymmetricTensor<2, 3> new_stress;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        new_stress.access_raw_entry(
          SymmetricTensor<2, 3>::component_to_unrolled_index(
            TableIndices<2>(i, j))) = rotated[i][j];
    return new_stress;
  }



  template <int dim>
  double
  LinearElastic<dim>::strain_energy_density(
    const SymmetricTensor<2, 3> &stress) const
  {
    return isotropic_strain_energy_density(stress,
                                           youngs_modulus,
                                           poissons_ratio);
  }



  template <int dim>
  double
  LinearElastic<dim>::wave_speed() const
  {
    return dilatational_wave_speed;
  }



  template <int dim>
  double
  LinearElastic<dim>::density() const
  {
    return mass_density;
  }



  template class LinearElastic<2>;
  template class LinearElastic<3>;

  GRAINMPM_REGISTER_CONSTITUTIVE_MODEL(LinearElastic,
                                       ConstitutiveModelParameters,
                                       "linear elastic",
                                       "hypoelastic, Jaumann-rotated")
} // namespace grainmpm
