// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_materials_von_mises_h
#define grainmpm_materials_von_mises_h

#include <grainmpm/materials/linear_elastic.h>

namespace grainmpm
{
  /**
   * Elastic-plastic material: hypoelastic (Jaumann-rotated) isotropic
   * elasticity with von Mises (J2) plasticity and linear isotropic
   * hardening, updated by radial return (doc/theory.md section 13;
   * Simo & Hughes 1998, box 3.1; the small-strain rate form of Sulsky,
   * Zhou & Schreyer 1995):
   *
   *   sigma_tr = sigma* + lambda tr(de) I + 2 mu de,   sigma* the rotated
   *   old stress; q_tr = sqrt(3/2 s_tr : s_tr), s = dev(sigma);
   *   f_tr = q_tr - (sigma_y + H epsilon_p);
   *   if f_tr > 0: d epsilon_p = f_tr / (3 mu + H),
   *                s = (1 - 3 mu d epsilon_p / q_tr) s_tr.
   *
   * The return is exact for linear hardening, so the new state lies on the
   * yield surface q = sigma_y + H epsilon_p to round-off. The history
   * variable is the equivalent plastic strain epsilon_p
   * = integral sqrt(2/3 de_p : de_p).
   *
   * Plane strain has de_zz = 0 and keeps sigma_zz. Plane stress finds
   * de_zz with sigma_zz = 0 by a scalar Newton iteration on the same 3D
   * return (the consistent tangent T_zzzz as slope); for elastic steps the
   * first iterate is exact and equals the reduced plane-stress law of
   * LinearElastic.
   *
   * update_stress() is a pure function of its arguments, as the implicit
   * residual requires. Elastic energy, density and wave speed are those of
   * the LinearElastic base.
   */
  /**
   * The entries of `Constitutive model = von Mises` in a material's
   * subsection: `Yield stress` and `Hardening modulus`.
   */
  class VonMisesParameters : public ConstitutiveModelParameters
  {
  public:
    void
    declare(ParameterHandler &prm) override;

    void
    check(const std::string &prefix) const override;

    /** Refuses an initial stress above the initial yield stress. */
    std::string
    check_initial_stress(const SymmetricTensor<2, 3> &stress,
                         const std::string           &where,
                         const std::string           &prefix) const override;

    std::string
    fingerprint() const override;

    /** The initial uniaxial yield stress sigma_y. */
    double yield_stress = 0.;
    /** The plastic modulus H of linear isotropic hardening. */
    double hardening_modulus = 0.;
  };



  template <int dim>
  class VonMises : public LinearElastic<dim>
  {
  public:
    /**
     * @p yield_stress is the initial uniaxial yield stress sigma_y,
     * @p hardening_modulus the plastic modulus H = d sigma_Y / d epsilon_p
     * (from a bilinear curve with tangent modulus E_t: H = E E_t / (E - E_t)).
     */
    VonMises(const double              density,
             const double              youngs_modulus,
             const double              poissons_ratio,
             const double              yield_stress,
             const double              hardening_modulus,
             const TwoDimensionalModel model);

    /** The model of @p material, with its VonMisesParameters. */
    VonMises(const MaterialParameters &material,
             const TwoDimensionalModel model);

    SymmetricTensor<2, 3>
    update_stress(const SymmetricTensor<2, 3> &stress,
                  const Tensor<2, dim>        &displacement_gradient_increment,
                  double                      &plastic_strain) const override;

    bool
    has_history() const override;

    double
    plastic_work_density(const SymmetricTensor<2, 3> &new_stress,
                         const double plastic_strain_increment) const override;

  private:
    /**
     * The 3D radial return from @p rotated (the rotated old stress) with
     * the 3D strain increment @p strain; returns the new stress, sets the
     * plastic strain increment and the tangent component T_zzzz.
     */
    SymmetricTensor<2, 3>
    radial_return(const SymmetricTensor<2, 3> &rotated,
                  const SymmetricTensor<2, 3> &strain,
                  const double                 plastic_strain,
                  double                      &plastic_increment,
                  double                      &tangent_zzzz) const;

    using LinearElastic<dim>::mu;
    using LinearElastic<dim>::plane_stress;
    using LinearElastic<dim>::youngs_modulus;

    const double yield_stress;
    const double hardening_modulus;
    /** Lame's first parameter in 3D (not reduced for plane stress). */
    const double lambda_3d;
  };
} // namespace grainmpm

#endif
