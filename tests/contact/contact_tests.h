// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Helpers of the contact-law tests: a vector from its components and the
// name of a contact state.

#ifndef grainmpm_tests_contact_contact_tests_h
#define grainmpm_tests_contact_contact_tests_h

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/tensor.h>

/**
 * The vector (x, y) in 2D, (x, y, z) in 3D.
 */
template <int dim>
dealii::Tensor<1, dim>
vec(const double x, const double y, const double z = 0.)
{
  dealii::Tensor<1, dim> v;
  v[0] = x;
  v[1] = y;
  if (dim == 3)
    v[dim - 1] = z;
  return v;
}

/**
 * "free", "sliding" or "sticking".
 */
inline const char *
state_name(const grainmpm::ContactState state)
{
  return state == grainmpm::ContactState::free    ? "free" :
         state == grainmpm::ContactState::sliding ? "sliding" :
                                                    "sticking";
}

#endif
