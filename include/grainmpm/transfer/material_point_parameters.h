// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_material_point_parameters_h
#define grainmpm_transfer_material_point_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace grainmpm
{
  /**
   * The shape functions of the particle-grid transfer (subsection
   * "Material points").
   */
  enum class ShapeFunctions
  {
    /** The Q1 hats S_i(x_p) of the grid (classic MPM). */
    linear,
    /**
     * Q1 hats averaged over a fixed box around each point (uGIMP,
     * Bardenhagen & Kober 2004).
     */
    ugimp,
    /**
     * Q1 hats averaged over a box that stretches with the deformation
     * (cpGIMP, Wallstedt & Guilkey 2008).
     */
    cpgimp
  };

  /**
   * Subsection "Material points".
   */
  struct MaterialPointParameters
  {
    unsigned int   particles_per_cell   = 2;
    std::string    shape_functions_text = "uGIMP";
    ShapeFunctions shape_functions      = ShapeFunctions::ugimp;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };
} // namespace grainmpm

#endif
