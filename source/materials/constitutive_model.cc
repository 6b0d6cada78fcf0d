// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/materials/constitutive_model_factory.h>

namespace grainmpm
{
  double
  isotropic_strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                  const double                 youngs_modulus,
                                  const double                 poissons_ratio)
  {
    const double E  = youngs_modulus;
    const double nu = poissons_ratio;
    const double normal =
      stress[0][0] * stress[0][0] + stress[1][1] * stress[1][1] +
      stress[2][2] * stress[2][2] -
      2. * nu *
        (stress[0][0] * stress[1][1] + stress[1][1] * stress[2][2] +
         stress[2][2] * stress[0][0]);
    const double shear = stress[0][1] * stress[0][1] +
                         stress[0][2] * stress[0][2] +
                         stress[1][2] * stress[1][2];
    return normal / (2. * E) + (1. + nu) * shear / E;
  }



  template <int dim>
  std::unique_ptr<ConstitutiveModel<dim>>
  create_constitutive_model(const MaterialParameters &material,
                            const TwoDimensionalModel model)
  {
    std::unique_ptr<ConstitutiveModel<dim>> result =
      ConstitutiveModelFactory::create<dim>(material, model);
    result->set_kirchhoff_rate(material.hypoelastic_stress == "Kirchhoff");
    return result;
  }



  template std::unique_ptr<ConstitutiveModel<2>>
  create_constitutive_model<2>(const MaterialParameters &,
                               const TwoDimensionalModel);
  template std::unique_ptr<ConstitutiveModel<3>>
  create_constitutive_model<3>(const MaterialParameters &,
                               const TwoDimensionalModel);
} // namespace grainmpm
