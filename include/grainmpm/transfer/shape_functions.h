// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_shape_functions_h
#define grainmpm_transfer_shape_functions_h

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  /**
   * The one-dimensional hat N(u) = max(0, 1 - |u|) (u in cells from the
   * node) of which the shape functions are made: the Q1 hats are its
   * products, the GIMP weights its averages over a particle's box
   * (TransferCache). Its integral Phi, the inverse of Phi and the centroid
   * of the half hat's weight also give where a flat surface lies that
   * fills a given fraction of a node's support or whose material has a
   * given centroid (the gap check of the contact law).
   */
  namespace HatKernel
  {
    /** N(u) = max(0, 1 - |u|). */
    inline double
    value(const double u)
    {
      return std::max(0., 1. - std::abs(u));
    }

    /**
     * Phi(u), the integral of the hat from -infinity to u, on its rising
     * piece -1 <= u <= 0: (1 + u)^2 / 2. Phi is 0 below and 1 above the
     * hat, and the two pieces meet at Phi(0) = 1/2; each is exact at its
     * ends, so a caller that knows the piece of u needs no tests.
     */
    inline double
    rising_integral(const double u)
    {
      return 0.5 * (1. + u) * (1. + u);
    }

    /** Phi(u) on the falling piece 0 <= u <= 1: 1 - (1 - u)^2 / 2. */
    inline double
    falling_integral(const double u)
    {
      return 1. - 0.5 * (1. - u) * (1. - u);
    }

    /**
     * The inverse of Phi on [-1, 1]: the u with Phi(u) = @p phi
     * (clamped to [0, 1]). A flat surface whose material fills the
     * fraction phi of a node's support lies at u = Phi^{-1}(phi) cells
     * along the normal.
     */
    inline double
    inverse_integral(double phi)
    {
      phi = std::min(1., std::max(0., phi));
      return phi <= 0.5 ? -1. + std::sqrt(2. * phi) :
                          1. - std::sqrt(2. * (1. - phi));
    }

    /**
     * The inverse for the half hat of a node on a box face (u in [0, 1]
     * into the box): the u at which the hat beyond u holds the fraction
     * @p phi (at most 1) of the half hat's integral, 2 int_u^1 N = (1 -
     * u)^2 = phi. A flat surface whose material fills the fraction phi of
     * the in-box support lies u = 1 - sqrt(phi) cells from the face.
     */
    inline double
    inverse_half_integral(const double phi)
    {
      return 1. - std::sqrt(std::min(1., phi));
    }

    /**
     * For the half hat of a node on a box face (u in [0, 1] into the box):
     * material from u to 1 has its weighted centroid int_u^1 t N / int_u^1 N
     * at (1 + 2 u) / 3 cells from the face, so a flat surface whose
     * material has its centroid at @p centroid cells lies
     * (3 centroid - 1) / 2 cells from the face (clamped to [0, 1]). Unlike
     * the filled fraction, the centroid does not change when the material
     * covers only a part of the support along the face (a grain's corner
     * at the node).
     */
    inline double
    half_surface_from_centroid(const double centroid)
    {
      return std::min(1., std::max(0., 0.5 * (3. * centroid - 1.)));
    }
  } // namespace HatKernel
} // namespace grainmpm

#endif
