// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_materials_material_parameters_h
#define grainmpm_materials_material_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <map>
#include <memory>
#include <string>

namespace grainmpm
{
  /**
   * The entries that one constitutive model adds to a material's
   * subsection, beyond those every material has (MaterialParameters). Each
   * model registered with ConstitutiveModelFactory has a class derived
   * from this one; every material holds one object of each, so that all
   * entries are declared before the file is read, and the chosen model's
   * object is checked and used.
   */
  class ConstitutiveModelParameters
  {
  public:
    virtual ~ConstitutiveModelParameters() = default;

    /** Declare the model's entries, bound to members, in @p prm. */
    virtual void
    declare(ParameterHandler &prm);

    /**
     * Check the values when the model is chosen: throw an InputError
     * naming the entry, whose path starts with @p prefix
     * ("Materials/NAME/").
     */
    virtual void
    check(const std::string &prefix) const;

    /**
     * What is wrong with the initial stress @p stress of a material point
     * @p where (" at the point (x y)") for this model, as the end of a
     * sentence that starts with the entry that gave it; empty if it is
     * admissible. @p prefix is the path of the material's entries.
     */
    virtual std::string
    check_initial_stress(const SymmetricTensor<2, 3> &stress,
                         const std::string           &where,
                         const std::string           &prefix) const;

    /**
     * The model's values for the fingerprint of a run (see
     * CheckpointManager::fingerprint()): ", name value" for each entry
     * that changes the results; empty if none.
     */
    virtual std::string
    fingerprint() const;
  };



  /**
   * One named material in subsection "Materials": the entries every
   * material has, and those of the constitutive models.
   */
  struct MaterialParameters
  {
    /** Makes the entries of every registered model, with their defaults. */
    MaterialParameters();

    std::string name;
    /** The name of the constitutive model (ConstitutiveModelFactory). */
    std::string constitutive_model = "linear elastic";
    double      density            = 1.;
    double      youngs_modulus     = 1.;
    double      poissons_ratio     = 0.3;
    /** Photoelastic output: specimen thickness and material fringe value. */
    double thickness             = 1.;
    double material_fringe_value = 0.;
    /** Expressions of the initial stress (empty: zero). */
    std::string initial_stress;
    /**
     * The stress whose Jaumann rate the model gives: "Kirchhoff"
     * (tau = J sigma, stored energy V0 W(tau)) or "Cauchy" (sigma, energy
     * V W(sigma)); doc/theory.md section 13.
     */
    std::string hypoelastic_stress = "Kirchhoff";
    /** The entries of every registered model, by the model's name. */
    std::map<std::string, std::shared_ptr<ConstitutiveModelParameters>>
      model_parameters;

    /** The entries of the chosen model. */
    const ConstitutiveModelParameters &
    get_model_parameters() const;

    /**
     * The entries of the model @p model_name, as the class @p Model of
     * that model's parameters.
     */
    template <class Model>
    Model &
    get_model_parameters(const std::string &model_name)
    {
      return dynamic_cast<Model &>(*model_parameters.at(model_name));
    }

    template <class Model>
    const Model &
    get_model_parameters(const std::string &model_name) const
    {
      return dynamic_cast<const Model &>(*model_parameters.at(model_name));
    }

    void
    declare(ParameterHandler &prm);
    void
    check();
  };



  /**
   * The syntax of the `Initial stress` entries of materials and grains, for
   * their documentation.
   */
  inline std::string
  initial_stress_syntax()
  {
    return "Stress of the material points at the start, as expressions of "
           "x, y (, z) separated by ';' (tension positive): in 2D "
           "'s_xx; s_yy; s_xy' (then s_zz = nu (s_xx + s_yy) in plane strain "
           "and 0 in plane stress) or 's_xx; s_yy; s_xy; s_zz', in 3D "
           "'s_xx; s_yy; s_zz; s_xy; s_xz; s_yz'; e.g. the lithostatic state "
           "of a layer of height 1 with rho g = 1 and K0 = 0.5: "
           "'-0.5*(1 - y); -(1 - y); 0'. ";
  }
} // namespace grainmpm

#endif
