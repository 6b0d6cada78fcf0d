// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/contact/contact_parameters.h>

#include <deal.II/base/patterns.h>

namespace grainmpm
{
  // ------------------------------------------------------------- contact

  void
  ContactParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.add_parameter(
      "Contact model",
      model_text,
      "How grains interact where they meet. 'none': all deformable grains "
      "share one grid velocity field, so touching grains stick (classic "
      "single-field MPM). 'frictionless': Bardenhagen-Brackbill-Sulsky "
      "contact, every grain has its own field; no interpenetration, free "
      "separation, no tangential force. 'Coulomb friction': the same with "
      "Coulomb friction (stick/slip) of coefficient 'Friction coefficient'. "
      "Dimensionless.",
      Patterns::Selection("none|frictionless|Coulomb friction"));
    prm.add_parameter("Friction coefficient",
                      friction_coefficient,
                      "Coulomb friction coefficient between grains, used by "
                      "the 'Coulomb friction' model. Dimensionless.",
                      Patterns::Double(0.));
    prm.add_parameter(
      "Gap check",
      gap_check,
      "Whether contact (between grains, with rigid grains and with the "
      "walls) acts only where the surfaces meet within the step. At each "
      "node the surface of every grain is located along the contact normal "
      "from the volume its material points give the node (sum_p V_p S_ip) "
      "against the node's support, as for a flat surface (a rigid grain "
      "from its shape); a grain that approaches its partner by less than the gap between the surfaces in "
      "one step is left alone; one that approaches faster is held (the "
      "explicit scheme removes its whole approach, the implicit one lets "
      "it close the gap and no more). 'false': the classic multi-field law, "
      "every approach at a node where two grains have mass is removed "
      "(contact about one cell early, grains rotating next to a surface "
      "are pushed off it, rolling grains slip, loose packings carry load "
      "through gaps).",
      Patterns::Bool());
    prm.add_parameter(
      "Shape gap",
      shape_gap,
      "With the gap check: whether an elastic disk or sphere (a grain of a "
      "material without history variable, alone in its field) is located "
      "where it meets a wall or a rigid grain from its shape placed at its "
      "centre of mass instead of from its material points, while its mean "
      "strain times its radius is below a tenth of a cell and where the "
      "shape agrees with its points within half a cell (doc/theory.md "
      "section 5.2). The points' surface follows their lattice, which "
      "turns with the grain: 'false' catches the side of a spinning or "
      "rolling disk that the rotation brings down early, and a pressed "
      "spinning disk loses spin and bounces.",
      Patterns::Bool());
    prm.add_parameter(
      "Light field fraction",
      light_field_fraction,
      "At a contact node, a grain's field with less mass than this fraction "
      "of the heaviest deformable field there takes no part in the contact "
      "law: it is left alone and does not count for the partner velocity. "
      "Such a field is the edge of a grain whose material points barely "
      "reach the node; its velocity carries no information, and holding it "
      "makes the implicit contact status cycle (doc/theory.md section 5.3). "
      "Rigid fields are never light. Zero: every field with mass takes "
      "part. Dimensionless.",
      Patterns::Double(0., 0.5));
    prm.leave_subsection();
  }



  void
  ContactParameters::check()
  {
    model =
      parse_choice<ContactModel>("Contact/Contact model = " + model_text,
                                 model_text,
                                 {{"none", ContactModel::none},
                                  {"frictionless", ContactModel::frictionless},
                                  {"Coulomb friction",
                                   ContactModel::coulomb_friction}});
  }
} // namespace grainmpm
