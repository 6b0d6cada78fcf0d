// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Light fields at a contact node (Contact/Light field fraction,
// doc/theory.md section 5.3): a deformable field with less mass than the
// fraction times the heaviest deformable field at the node is left alone
// by the contact law, deciding (ContactLaw::project_node) and frozen
// (ContactLaw::project_node_frozen), and does not count for the partner
// velocity. With the fraction 0 (the law before) the light field's
// velocity moves the heavy one. Fields above the fraction, and rigid
// fields whatever their mass, are treated as before.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include <cstring>

#include "../tests.h"

#include "contact_tests.h"

using namespace grainmpm;

template <int dim>
Tensor<1, dim>
filtered(Tensor<1, dim> v)
{
  for (unsigned int d = 0; d < dim; ++d)
    v[d] = filter_out_small_numbers(v[d], 1e-14);
  return v;
}

template <int dim>
bool
same(const Tensor<1, dim> &a, const Tensor<1, dim> &b)
{
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}



// Fields 0 (heavy, mass 1) and 1 (mass m_1) of two grains, approaching
// each other along n; field 1 fast, as a light field is.
template <int dim>
void
pair(const double m_1, const double fraction)
{
  const Tensor<1, dim> n          = vec<dim>(0., 1.);
  const double         masses[2]  = {1., m_1};
  const bool           rigid[2]   = {false, false};
  const Tensor<1, dim> normals[2] = {n, -n};
  const Tensor<1, dim> v_0 = vec<dim>(0.01, 0.02), v_1 = vec<dim>(-1.3, -2.6);
  Tensor<1, dim>       velocities[2] = {v_0, v_1};
  ContactState         states[2];
  Tensor<1, dim>       slips[2], reference;
  ContactNode<dim>     node{2, masses, rigid, normals, velocities};
  node.states          = states;
  node.slip_directions = slips;
  node.reference       = &reference;
  node.light_fraction  = fraction;
  const bool corrected =
    ContactLaw<dim>::project_node({ContactModel::coulomb_friction, 0.3}, node);
  deallog << "m_1 = " << m_1 << ", fraction = " << fraction << ": returns "
          << (corrected ? "true" : "false") << ", states "
          << state_name(states[0]) << ' ' << state_name(states[1])
          << ", heavy field unchanged: "
          << (same(velocities[0], v_0) ? "yes" : "no")
          << ", light field unchanged: "
          << (same(velocities[1], v_1) ? "yes" : "no") << std::endl;
  deallog << "  heavy field's velocity change " << filtered(velocities[0] - v_0)
          << ", momentum change "
          << filtered<dim>(masses[0] * (velocities[0] - v_0) +
                           masses[1] * (velocities[1] - v_1))
          << std::endl;

  // The same node with the states frozen as "held" (sticking), as an
  // implicit status that held the light field would have them.
  Tensor<1, dim>     frozen[2] = {v_0, v_1};
  const ContactState held[2] = {ContactState::sticking, ContactState::sticking};
  ContactNode<dim>   frozen_node{2, masses, rigid, normals, frozen};
  frozen_node.light_fraction = fraction;
  ContactLaw<dim>::project_node_frozen(frozen_node, held, slips, 0.3);
  deallog << "  frozen, both held: heavy field's velocity change "
          << filtered(frozen[0] - v_0) << ", light field unchanged: "
          << (same(frozen[1], v_1) ? "yes" : "no") << std::endl;
}



// Three grains: heavy fields 0 and 2 pressed together, light field 1
// fast. With the fraction the result for fields 0 and 2 is that of the
// node without field 1, to the bit.
template <int dim>
void
three_fields()
{
  const Tensor<1, dim> n             = vec<dim>(1., 0.);
  const double         masses[3]     = {1., 1e-6, 0.8};
  const bool           rigid[3]      = {false, false, false};
  const Tensor<1, dim> normals[3]    = {n, vec<dim>(0., -1.), -n};
  const Tensor<1, dim> v[3]          = {vec<dim>(0.2, 0.1),
                                        vec<dim>(3., 4.),
                                        vec<dim>(-0.1, 0.05)};
  Tensor<1, dim>       with_light[3] = {v[0], v[1], v[2]};
  ContactNode<dim>     node{3, masses, rigid, normals, with_light};
  node.light_fraction = 1e-3;
  ContactLaw<dim>::project_node({ContactModel::coulomb_friction, 0.3}, node);

  const double         masses_2[2]  = {masses[0], masses[2]};
  const Tensor<1, dim> normals_2[2] = {normals[0], normals[2]};
  Tensor<1, dim>       without[2]   = {v[0], v[2]};
  ContactLaw<dim>::project_node({ContactModel::coulomb_friction, 0.3},
                                {2, masses_2, rigid, normals_2, without});
  deallog
    << "three fields, one light: heavy fields as without it: "
    << (same(with_light[0], without[0]) && same(with_light[2], without[1]) ?
          "yes" :
          "no")
    << ", light field unchanged: " << (same(with_light[1], v[1]) ? "yes" : "no")
    << ", heavy fields' relative normal velocity after "
    << filter_out_small_numbers((with_light[0] - with_light[2]) * n, 1e-14)
    << std::endl;
}



// A rigid field of any mass is never light, and a single deformable
// field against it is not light either (the heaviest deformable field).
template <int dim>
void
rigid_partner()
{
  const Tensor<1, dim> n          = vec<dim>(0., -1.);
  const bool           rigid[3]   = {false, true, false};
  const Tensor<1, dim> normals[3] = {n, -n, n};
  const Tensor<1, dim> v_rigid    = vec<dim>(0., 0.);
  for (const double rigid_mass : {1., 1e9})
    {
      const double     masses[3]     = {1e-4, rigid_mass, 1e-9};
      Tensor<1, dim>   velocities[3] = {vec<dim>(0.1, -0.5),
                                        v_rigid,
                                        vec<dim>(0.4, -2.)};
      ContactNode<dim> node{3, masses, rigid, normals, velocities};
      node.light_fraction = 1e-3;
      ContactLaw<dim>::project_node({ContactModel::frictionless, 0.}, node);
      deallog << "rigid partner of mass " << rigid_mass
              << ": deformable field of mass 1e-4 after " << velocities[0]
              << ", light field (1e-9) after " << velocities[2] << std::endl;
    }
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  pair<dim>(2e-9, 0.);
  pair<dim>(2e-9, 1e-3);
  pair<dim>(2e-3, 0.);
  pair<dim>(2e-3, 1e-3);
  three_fields<dim>();
  rigid_partner<dim>();
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
