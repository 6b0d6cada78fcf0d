// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/materials/constitutive_model_factory.h>
#include <grainmpm/materials/von_mises.h>

#include <deal.II/base/patterns.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    /** q = sqrt(3/2 s : s) of a stress. */
    double
    equivalent_stress(const SymmetricTensor<2, 3> &stress)
    {
      const SymmetricTensor<2, 3> s = deviator(stress);
      return std::sqrt(1.5 * (s * s));
    }
  } // namespace



  void
  VonMisesParameters::declare(ParameterHandler &prm)
  {
    prm.add_parameter("Yield stress",
                      yield_stress,
                      "von Mises: the initial uniaxial yield stress sigma_y "
                      "(the von Mises stress q = sqrt(3/2 s:s) at first "
                      "yield). Must be positive for 'von Mises'; ignored "
                      "otherwise. Units: stress.",
                      Patterns::Double(0.));
    prm.add_parameter("Hardening modulus",
                      hardening_modulus,
                      "von Mises: the plastic modulus H of linear isotropic "
                      "hardening, sigma_Y = sigma_y + H epsilon_p (from a "
                      "bilinear curve with tangent modulus E_t: "
                      "H = E E_t / (E - E_t)); 0 is perfect plasticity. "
                      "Units: stress.",
                      Patterns::Double(0.));
  }



  void
  VonMisesParameters::check(const std::string &prefix) const
  {
    if (!(yield_stress > 0.))
      throw InputError(prefix + "Yield stress",
                       "must be positive for the 'von Mises' model, but is " +
                         std::to_string(yield_stress) + ".");
  }



  std::string
  VonMisesParameters::check_initial_stress(const SymmetricTensor<2, 3> &stress,
                                           const std::string           &where,
                                           const std::string &prefix) const
  {
    const double equivalent = equivalent_stress(stress);
    if (!(equivalent > yield_stress * (1. + 1e-12)))
      return "";
    std::ostringstream message;
    message << "its von Mises stress " << equivalent << where
            << " is above the yield stress " << yield_stress << " of " << prefix
            << "Yield stress: an initial stress must be admissible.";
    return message.str();
  }



  std::string
  VonMisesParameters::fingerprint() const
  {
    std::ostringstream out;
    out << std::setprecision(17) << ", yield stress " << yield_stress
        << ", hardening modulus " << hardening_modulus;
    return out.str();
  }



  template <int dim>
  VonMises<dim>::VonMises(const MaterialParameters &material,
                          const TwoDimensionalModel model)
    : VonMises(material.density,
               material.youngs_modulus,
               material.poissons_ratio,
               material.get_model_parameters<VonMisesParameters>("von Mises")
                 .yield_stress,
               material.get_model_parameters<VonMisesParameters>("von Mises")
                 .hardening_modulus,
               model)
  {}



  template <int dim>
  VonMises<dim>::VonMises(const double              density,
                          const double              youngs_modulus,
                          const double              poissons_ratio,
                          const double              yield_stress,
                          const double              hardening_modulus,
                          const TwoDimensionalModel model)
    : LinearElastic<dim>(density, youngs_modulus, poissons_ratio, model)
    , yield_stress(yield_stress)
    , hardening_modulus(hardening_modulus)
    , lambda_3d(youngs_modulus * poissons_ratio /
                ((1. + poissons_ratio) * (1. - 2. * poissons_ratio)))
  {}



  template <int dim>
  SymmetricTensor<2, 3>
  VonMises<dim>::radial_return(const SymmetricTensor<2, 3> &rotated,
                               const SymmetricTensor<2, 3> &strain,
                               const double                 plastic_strain,
                               double                      &plastic_increment,
                               double                      &tangent_zzzz) const
  {
    const SymmetricTensor<2, 3> trial =
      rotated + lambda_3d * trace(strain) * unit_symmetric_tensor<3>() +
      2. * mu * strain;
    const SymmetricTensor<2, 3> s_trial = deviator(trial);
    const double                q_trial = std::sqrt(1.5 * (s_trial * s_trial));
    const double                f_trial =
      q_trial - (yield_stress + hardening_modulus * plastic_strain);
    if (!(f_trial > 0.))
      {
        plastic_increment = 0.;
        tangent_zzzz      = lambda_3d + 2. * mu;
        return trial;
      }
    plastic_increment  = f_trial / (3. * mu + hardening_modulus);
    const double beta  = 1. - 3. * mu * plastic_increment / q_trial;
    const double kappa = lambda_3d + 2. * mu / 3.;
    // The consistent tangent (Simo & Hughes 1998), its zz-zz component, with
    // N = s / |s| (unit Frobenius norm).
    const double n_zz = s_trial[2][2] / s_trial.norm();
    const double gamma_bar =
      1. / (1. + hardening_modulus / (3. * mu)) - (1. - beta);
    tangent_zzzz =
      kappa + 2. * mu * beta * (2. / 3.) - 2. * mu * gamma_bar * n_zz * n_zz;
    return beta * s_trial + (trace(trial) / 3.) * unit_symmetric_tensor<3>();
  }



  template <int dim>
  SymmetricTensor<2, 3>
  VonMises<dim>::update_stress(
    const SymmetricTensor<2, 3> &stress,
    const Tensor<2, dim>        &displacement_gradient_increment,
    double                      &plastic_strain) const
  {
    // Strain and spin increments in 3D components (zero out of plane).
    const Tensor<2, dim> &L = displacement_gradient_increment;
    Tensor<2, 3>          spin;
    SymmetricTensor<2, 3> strain;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        {
          spin[i][j] = 0.5 * (L[i][j] - L[j][i]);
          if (j >= i)
            strain[i][j] = 0.5 * (L[i][j] + L[j][i]);
        }

    // Jaumann rotation of the old stress: sigma + dW sigma - sigma dW.
    const Tensor<2, 3>          old = stress;
    const SymmetricTensor<2, 3> rotated =
      symmetrize(old + spin * old - old * spin);

    double                plastic_increment = 0.;
    double                tangent_zzzz      = lambda_3d + 2. * mu;
    SymmetricTensor<2, 3> new_stress;
    if (!plane_stress)
      new_stress = radial_return(
        rotated, strain, plastic_strain, plastic_increment, tangent_zzzz);
    else
      {
        // Find de_zz with sigma_zz = 0: the elastic guess is exact for an
        // elastic step; plastic steps converge in a few Newton steps.
        const double scale = std::abs(yield_stress) + rotated.norm() +
                             youngs_modulus * strain.norm();
        strain[2][2] =
          -(rotated[2][2] + lambda_3d * trace(strain)) / (lambda_3d + 2. * mu);
        for (unsigned int iteration = 0;; ++iteration)
          {
            new_stress = radial_return(
              rotated, strain, plastic_strain, plastic_increment, tangent_zzzz);
            if (std::abs(new_stress[2][2]) <= 1e-13 * scale)
              break;
            AssertThrow(iteration < 50,
                        ExcMessage("the plane-stress return of the von Mises "
                                   "model did not converge"));
            strain[2][2] -= new_stress[2][2] / tangent_zzzz;
          }
        new_stress[2][2] = 0.;
      }
    plastic_strain += plastic_increment;
    return new_stress;
  }



  template <int dim>
  double
  VonMises<dim>::plastic_work_density(
    const SymmetricTensor<2, 3> &new_stress,
    const double                 plastic_strain_increment) const
  {
    // sigma : de_p with de_p = 3/2 d epsilon_p s / q: q d epsilon_p.
    return equivalent_stress(new_stress) * plastic_strain_increment;
  }



  template <int dim>
  bool
  VonMises<dim>::has_history() const
  {
    return true;
  }



  template class VonMises<2>;
  template class VonMises<3>;

  GRAINMPM_REGISTER_CONSTITUTIVE_MODEL(
    VonMises,
    VonMisesParameters,
    "von Mises",
    "the same elasticity with J2 plasticity and linear isotropic hardening, "
    "radial return; needs Yield stress")
} // namespace grainmpm
