// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_materials_linear_elastic_h
#define grainmpm_materials_linear_elastic_h

#include <grainmpm/materials/constitutive_model.h>

namespace grainmpm
{
  /**
   * Hypoelastic isotropic linear elasticity with the Jaumann-rotated old
   * stress (doc/theory.md section 13):
   * sigma^{n+1} = sigma^n + dW sigma^n - sigma^n dW + lambda tr(de) I
   * + 2 mu de, with de = sym(dt grad v), dW = skew(dt grad v). In 2D the
   * plane-strain increment has de_zz = 0 (sigma_zz follows), the
   * plane-stress increment keeps sigma_zz = 0.
   */
  template <int dim>
  class LinearElastic : public ConstitutiveModel<dim>
  {
  public:
    LinearElastic(const double              density,
                  const double              youngs_modulus,
                  const double              poissons_ratio,
                  const TwoDimensionalModel model);

    /** The elasticity of @p material. */
    LinearElastic(const MaterialParameters &material,
                  const TwoDimensionalModel model);

    SymmetricTensor<2, 3>
    update_stress(const SymmetricTensor<2, 3> &stress,
                  const Tensor<2, dim>        &displacement_gradient_increment,
                  double                      &plastic_strain) const override;

    double
    strain_energy_density(const SymmetricTensor<2, 3> &stress) const override;

    double
    wave_speed() const override;

    std::pair<double, double>
    lame_parameters() const override
    {
      return {lambda, mu};
    }

    double
    density() const override;

  protected:
    const double mass_density;
    const double youngs_modulus;
    const double poissons_ratio;
    /** True for the plane-stress idealisation in 2D: sigma_zz stays 0. */
    const bool plane_stress;
    /** Lame's first parameter of the increment (reduced in plane stress). */
    double lambda;
    /** Shear modulus. */
    double mu;
    double dilatational_wave_speed;
  };
} // namespace grainmpm

#endif
