// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_contact_parameters_h
#define grainmpm_contact_contact_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace grainmpm
{
  /**
   * How grains interact where they meet (subsection "Contact").
   */
  enum class ContactModel
  {
    none,
    frictionless,
    coulomb_friction
  };

  /**
   * Subsection "Contact".
   */
  struct ContactParameters
  {
    std::string  model_text           = "frictionless";
    ContactModel model                = ContactModel::frictionless;
    double       friction_coefficient = 0.;
    bool         gap_check            = true;
    bool         shape_gap            = true;
    double       light_field_fraction = 1e-3;

    void
    declare(ParameterHandler &prm);
    void
    check();
  };
} // namespace grainmpm

#endif
