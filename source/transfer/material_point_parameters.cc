// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/transfer/material_point_parameters.h>

#include <deal.II/base/patterns.h>

namespace grainmpm
{
  // ----------------------------------------------------- material points

  void
  MaterialPointParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    prm.add_parameter("Particles per cell",
                      particles_per_cell,
                      "Number of material points per cell and direction in "
                      "a regular arrangement (2 gives 4 per cell in 2D). "
                      "Dimensionless.",
                      Patterns::Integer(1, 10));
    prm.add_parameter(
      "Shape functions",
      shape_functions_text,
      "The weights with which a material point talks to the grid nodes. "
      "'linear': the bilinear (trilinear) hat functions of the grid at the "
      "point (classic MPM; 2^dim nodes per point); a point crossing a cell "
      "face makes its force jump, which injects grid-scale noise. 'uGIMP': "
      "the hats averaged over the point's box (half the point spacing on "
      "each side; Bardenhagen & Kober 2004): the weights are C1 in the "
      "point position, up to 3^dim nodes per point. 'cpGIMP': the same with "
      "a box whose half-width along axis d grows with the deformation, "
      "sqrt((F F^T)_dd) times the initial one, at most half a cell "
      "(Wallstedt & Guilkey 2008). Near a box face the point's box is cut at "
      "the face, which keeps the partition of unity. uGIMP is the default: "
      "one wall impact's energy loss then falls under refinement, with "
      "linear it grows (doc/validation.md).",
      Patterns::Selection("linear|uGIMP|cpGIMP"));
    prm.leave_subsection();
  }



  void
  MaterialPointParameters::check()
  {
    shape_functions =
      parse_choice<ShapeFunctions>("Material points/Shape functions = " +
                                     shape_functions_text,
                                   shape_functions_text,
                                   {{"linear", ShapeFunctions::linear},
                                    {"uGIMP", ShapeFunctions::ugimp},
                                    {"cpGIMP", ShapeFunctions::cpgimp}});
  }
} // namespace grainmpm
