// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_particle_fields_h
#define grainmpm_postprocess_particle_fields_h

#include <grainmpm/base/config.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <functional>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Principal stress difference of @p stress: in 2D the in-plane
   * sigma_1 - sigma_2 = sqrt((s_xx - s_yy)^2 + 4 s_xy^2) that photoelastic
   * fringes show, in 3D the largest minus the smallest principal stress.
   */
  template <int dim>
  double
  principal_stress_difference(const SymmetricTensor<2, 3> &stress);

  /** The von Mises equivalent stress sqrt(3/2 s:s) of @p stress. */
  double
  von_mises_stress(const SymmetricTensor<2, 3> &stress);

  /**
   * What a particle field is computed from: one material point.
   */
  template <int dim>
  struct MaterialPointView
  {
    /** The particle's properties (see MaterialPointLayout). */
    ArrayView<const double> properties;
    /** The particle's id. */
    types::particle_index id;
    /** Its stress, from the properties. */
    SymmetricTensor<2, 3> stress;
    /**
     * Thickness / material fringe value of its grain's material (0 if it
     * is not photoelastic).
     */
    double fringe_factor;
  };

  /**
   * One field of the material points in the particle output: its name in
   * the .vtu files, its number of components, how ParaView is to read
   * them, and how the values of a material point are computed.
   */
  template <int dim>
  struct ParticleField
  {
    std::string                                              name;
    unsigned int                                             n_components;
    DataComponentInterpretation::DataComponentInterpretation interpretation;
    /** Write the n_components values of the material point into values. */
    std::function<void(const MaterialPointView<dim> &point, double *values)>
      evaluate;
  };

  /**
   * The fields of the particle output, in the order they are written:
   * grain (counted from 1), id, velocity (vector), stress (dim x dim
   * tensor), in 2D stress_zz, principal_stress_difference, fringe_order,
   * von_mises_stress, volume, plastic_strain. A new output field is one
   * entry of this table.
   */
  template <int dim>
  const std::vector<ParticleField<dim>> &
  particle_fields();
} // namespace grainmpm

#endif
