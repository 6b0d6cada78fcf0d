// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_materials_constitutive_model_h
#define grainmpm_materials_constitutive_model_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <utility>

namespace grainmpm
{
  /**
   * The interface of a constitutive model: a pure function from the old
   * stress, the history and the increment of the displacement gradient
   * over a step (dt times the velocity gradient) to the new stress and
   * history (doc/theory.md section 13). Stresses are three-dimensional in every
   * dimension so that plane strain keeps sigma_zz.
   */
  template <int dim>
  class ConstitutiveModel
  {
  public:
    virtual ~ConstitutiveModel() = default;

    /**
     * The stress after an increment @p displacement_gradient_increment
     * (dt grad v, dimensionless) from the state @p stress. @p plastic_strain
     * is the history variable, updated in place by inelastic models.
     */
    virtual SymmetricTensor<2, 3>
    update_stress(const SymmetricTensor<2, 3> &stress,
                  const Tensor<2, dim>        &displacement_gradient_increment,
                  double                      &plastic_strain) const = 0;

    /**
     * Elastic strain energy per unit volume stored with stress @p stress,
     * 1/2 sigma : C^{-1} : sigma. Units: stress.
     */
    virtual double
    strain_energy_density(const SymmetricTensor<2, 3> &stress) const = 0;

    /** The largest wave speed, for the CFL condition. Units: length/time. */
    virtual double
    wave_speed() const = 0;

    /**
     * Lame's first parameter and the shear modulus of the elastic
     * increment (in 2D plane stress the reduced first parameter): the
     * tangent that the assembled preconditioner of the implicit scheme
     * uses. Units: stress.
     */
    virtual std::pair<double, double>
    lame_parameters() const = 0;

    /** Mass density. */
    virtual double
    density() const = 0;

    /**
     * Whether update_stress() reads and writes the history variable
     * (plastic strain); if not, callers may pass any value.
     */
    virtual bool
    has_history() const
    {
      return false;
    }

    /**
     * The plastic work per unit volume, sigma : de_p, of a step that ended
     * at @p new_stress and increased the equivalent plastic strain by
     * @p plastic_strain_increment. Zero for elastic models.
     */
    virtual double
    plastic_work_density(const SymmetricTensor<2, 3> & /*new_stress*/,
                         const double /*plastic_strain_increment*/) const
    {
      return 0.;
    }

    /**
     * Whether update_stress() acts on the Kirchhoff stress tau = J sigma
     * (the default) or on the Cauchy stress (Materials/NAME/Hypoelastic
     * stress). The points store the Cauchy stress either way; the
     * callers convert with rate_stress_factor().
     */
    void
    set_kirchhoff_rate(const bool kirchhoff)
    {
      kirchhoff_rate = kirchhoff;
    }

    /**
     * The factor that turns the Cauchy stress of a point with volume
     * @p volume (@p initial_volume at t = 0) into the stress update_stress()
     * acts on: J = V / V0 for the Kirchhoff stress, 1 for the Cauchy stress.
     */
    double
    rate_stress_factor(const double volume, const double initial_volume) const
    {
      return kirchhoff_rate ? volume / initial_volume : 1.;
    }

    /**
     * The volume that the stress of update_stress() and its energy density
     * are per: V0 (Kirchhoff) or @p volume (Cauchy). The elastic energy of
     * a point is energy_volume() times strain_energy_density() of
     * rate_stress_factor() times its Cauchy stress.
     */
    double
    energy_volume(const double volume, const double initial_volume) const
    {
      return kirchhoff_rate ? initial_volume : volume;
    }

    /** The elastic energy of a point with Cauchy stress @p stress. */
    double
    strain_energy(const SymmetricTensor<2, 3> &stress,
                  const double                 volume,
                  const double                 initial_volume) const
    {
      return energy_volume(volume, initial_volume) *
             strain_energy_density(rate_stress_factor(volume, initial_volume) *
                                   stress);
    }

  private:
    bool kirchhoff_rate = true;
  };

  /**
   * 1/2 sigma : C^{-1} : sigma of isotropic elasticity with Young's modulus
   * @p youngs_modulus and Poisson's ratio @p poissons_ratio, in 3D
   * components; with the plane-strain sigma_zz or the plane-stress
   * sigma_zz = 0 it is the corresponding 2D energy. Units: stress.
   */
  double
  isotropic_strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                  const double                 youngs_modulus,
                                  const double                 poissons_ratio);

  /**
   * Create the model named in @p material for the two-dimensional
   * idealisation @p model (ignored in 3D).
   */
  template <int dim>
  std::unique_ptr<ConstitutiveModel<dim>>
  create_constitutive_model(const MaterialParameters &material,
                            const TwoDimensionalModel model);
} // namespace grainmpm

#endif
