// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/materials/constitutive_model_factory.h>
#include <grainmpm/materials/material_parameters.h>

#include <deal.II/base/patterns.h>

namespace grainmpm
{
  void
  ConstitutiveModelParameters::declare(ParameterHandler &)
  {}



  void
  ConstitutiveModelParameters::check(const std::string &) const
  {}



  std::string
  ConstitutiveModelParameters::check_initial_stress(
    const SymmetricTensor<2, 3> &,
    const std::string &,
    const std::string &) const
  {
    return "";
  }



  std::string
  ConstitutiveModelParameters::fingerprint() const
  {
    return "";
  }



  MaterialParameters::MaterialParameters()
  {
    for (const auto &[name, model] : ConstitutiveModelFactory::models())
      model_parameters[name] = model.make_parameters();
  }



  const ConstitutiveModelParameters &
  MaterialParameters::get_model_parameters() const
  {
    return *model_parameters.at(constitutive_model);
  }



  void
  MaterialParameters::declare(ParameterHandler &prm)
  {
    prm.add_parameter("Constitutive model",
                      constitutive_model,
                      ConstitutiveModelFactory::documentation(),
                      Patterns::Selection(
                        ConstitutiveModelFactory::selection()));
    prm.add_parameter("Density",
                      density,
                      "Mass density in the reference configuration. Must be "
                      "positive. Units: mass/length^3 (mass/length^2 per "
                      "unit thickness in 2D).",
                      Patterns::Double(0.));
    prm.add_parameter("Young's modulus",
                      youngs_modulus,
                      "Young's modulus E. Must be positive. Units: "
                      "mass/(length time^2), i.e. stress.",
                      Patterns::Double(0.));
    prm.add_parameter("Poisson's ratio",
                      poissons_ratio,
                      "Poisson's ratio nu, in (-1, 0.5). Dimensionless.",
                      Patterns::Double(-1., 0.5));
    prm.add_parameter("Thickness",
                      thickness,
                      "Photoelastic output: thickness t of the specimen in "
                      "the fringe order N = t (sigma_1 - sigma_2) / f_sigma. "
                      "Units: length.",
                      Patterns::Double(0.));
    prm.add_parameter("Material fringe value",
                      material_fringe_value,
                      "Photoelastic output: the material fringe value "
                      "f_sigma (stress times length per fringe; Homalite-100 "
                      "about 23 kN/m). 0 means not photoelastic: the fringe "
                      "order is written as 0. Units: stress length.",
                      Patterns::Double(0.));
    prm.add_parameter("Initial stress",
                      initial_stress,
                      initial_stress_syntax() +
                        "The grains of this material start with it unless they "
                        "give their own; empty: zero. Units: stress.");
    prm.add_parameter(
      "Hypoelastic stress",
      hypoelastic_stress,
      "The stress whose Jaumann rate the elastic increment C : dt D gives. "
      "'Kirchhoff': tau = J sigma (J = V / V0); the elastic energy of a "
      "point, V0 W(tau), changes by the work of its stresses, and a purely "
      "volumetric motion gives Hencky's law tau = K ln J. 'Cauchy': sigma "
      "itself; the energy V W(sigma) differs from the work by the "
      "hypoelastic correction of the energy ledger. The points store and "
      "write the Cauchy stress either way; the two differ at first order "
      "in the strain. Dimensionless.",
      Patterns::Selection("Kirchhoff|Cauchy"));
    for (auto &[model_name, parameters] : model_parameters)
      parameters->declare(prm);
  }



  void
  MaterialParameters::check()
  {
    const std::string prefix = "Materials/" + name + "/";
    std::vector<std::pair<std::string, std::string>> names;
    for (const auto &[model_name, model] : ConstitutiveModelFactory::models())
      names.emplace_back(model_name, model_name);
    parse_choice<std::string>(prefix +
                                "Constitutive model = " + constitutive_model,
                              constitutive_model,
                              names);
    if (!(density > 0.))
      throw InputError(prefix + "Density",
                       "must be positive, but is " + std::to_string(density) +
                         ".");
    if (!(youngs_modulus > 0.))
      throw InputError(prefix + "Young's modulus",
                       "must be positive, but is " +
                         std::to_string(youngs_modulus) + ".");
    if (!(poissons_ratio > -1. && poissons_ratio < 0.5))
      throw InputError(prefix + "Poisson's ratio",
                       "must lie strictly between -1 and 0.5, but is " +
                         std::to_string(poissons_ratio) + ".");
    get_model_parameters().check(prefix);
  }
} // namespace grainmpm
