// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_material_point_layout_h
#define grainmpm_particles_material_point_layout_h

#include <grainmpm/base/config.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace grainmpm
{
  /**
   * The layout of the properties every material point carries in the
   * property pool of the `Particles::ParticleHandler`: the only place that
   * knows raw property indices. Everything else uses the accessors.
   *
   * The stress is always stored as a three-dimensional symmetric tensor
   * (6 numbers, SymmetricTensor<2,3> unrolled order xx, yy, zz, xy, xz, yz)
   * so that the out-of-plane stress of plane strain is kept in 2D.
   */
  template <int dim>
  struct MaterialPointLayout
  {
    /** Mass of the point; constant. Units: mass. */
    static constexpr unsigned int mass = 0;
    /** Current volume (area per unit thickness in 2D). */
    static constexpr unsigned int volume = 1;
    /** Volume at t = 0. */
    static constexpr unsigned int initial_volume = 2;
    /** Grain the point belongs to (stored as a double). */
    static constexpr unsigned int grain = 3;
    /** First of dim velocity components. */
    static constexpr unsigned int velocity = 4;
    /** First of 6 stress components. */
    static constexpr unsigned int stress = velocity + dim;
    /** First of dim*dim components of the deformation gradient F. */
    static constexpr unsigned int deformation_gradient = stress + 6;
    /** History: equivalent plastic strain (zero for elastic materials). */
    static constexpr unsigned int plastic_strain =
      deformation_gradient + dim * dim;
    /**
     * First of dim components of the point's mean acceleration over the
     * last implicit step, (v^{n+1} - v^n) / dt (StepErrorEstimator).
     */
    static constexpr unsigned int acceleration = plastic_strain + 1;
    /** Number of properties per point. */
    static constexpr unsigned int n_properties = acceleration + dim;

    static_assert(n_properties == 11 + 2 * dim + dim * dim,
                  "the layout must stay dense");

    /** The dim properties from @p first on, as a vector. */
    static Tensor<1, dim>
    get_vector(const ArrayView<const double> &properties,
               const unsigned int             first)
    {
      Tensor<1, dim> v;
      for (unsigned int d = 0; d < dim; ++d)
        v[d] = properties[first + d];
      return v;
    }

    /** Store @p v in the dim properties from @p first on. */
    static void
    set_vector(const Tensor<1, dim>    &v,
               const ArrayView<double> &properties,
               const unsigned int       first)
    {
      for (unsigned int d = 0; d < dim; ++d)
        properties[first + d] = v[d];
    }

    static Tensor<1, dim>
    get_velocity(const ArrayView<const double> &properties)
    {
      return get_vector(properties, velocity);
    }

    static void
    set_velocity(const Tensor<1, dim> &v, const ArrayView<double> &properties)
    {
      set_vector(v, properties, velocity);
    }

    static Tensor<1, dim>
    get_acceleration(const ArrayView<const double> &properties)
    {
      return get_vector(properties, acceleration);
    }

    static void
    set_acceleration(const Tensor<1, dim>    &a,
                     const ArrayView<double> &properties)
    {
      set_vector(a, properties, acceleration);
    }

    static SymmetricTensor<2, 3>
    get_stress(const ArrayView<const double> &properties)
    {
      SymmetricTensor<2, 3> sigma;
      for (unsigned int c = 0; c < 6; ++c)
        sigma.access_raw_entry(c) = properties[stress + c];
      return sigma;
    }

    static void
    set_stress(const SymmetricTensor<2, 3> &sigma,
               const ArrayView<double>     &properties)
    {
      for (unsigned int c = 0; c < 6; ++c)
        properties[stress + c] = sigma.access_raw_entry(c);
    }

    static Tensor<2, dim>
    get_deformation_gradient(const ArrayView<const double> &properties)
    {
      Tensor<2, dim> F;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F[i][j] = properties[deformation_gradient + dim * i + j];
      return F;
    }

    static void
    set_deformation_gradient(const Tensor<2, dim>    &F,
                             const ArrayView<double> &properties)
    {
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          properties[deformation_gradient + dim * i + j] = F[i][j];
    }

    static unsigned int
    get_grain(const ArrayView<const double> &properties)
    {
      return static_cast<unsigned int>(properties[grain]);
    }
  };
} // namespace grainmpm

#endif
