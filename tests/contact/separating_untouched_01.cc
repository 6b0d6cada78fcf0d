// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// ContactLaw::project_node leaves receding (and purely sliding) grains
// bit-for-bit unchanged (doc/theory.md section 5.2), and treats a rigid
// partner as infinite mass: the deformable grain gets the rigid
// velocity's normal component (and friction relative to it), the rigid
// velocity is not changed, whatever the rigid field's mass.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include <cstring>

#include "../tests.h"

#include "contact_tests.h"

using namespace grainmpm;

std::string
model_name(const ContactModel model)
{
  return model == ContactModel::frictionless     ? "frictionless" :
         model == ContactModel::coulomb_friction ? "Coulomb friction" :
                                                   "none";
}



// Two deformable grains that do not approach: nothing may change.
template <int dim>
void
not_approaching(const std::string    &name,
                const Tensor<1, dim> &n,
                const Tensor<1, dim> &v_a,
                const Tensor<1, dim> &v_b)
{
  const double         masses[2]  = {2., 5.};
  const bool           rigid[2]   = {false, false};
  const Tensor<1, dim> normals[2] = {n, -n};
  const Tensor<1, dim> v_cm       = (masses[0] * v_a + masses[1] * v_b) / 7.;
  deallog << name << ": (v_a - v_cm) . n_a = "
          << filter_out_small_numbers((v_a - v_cm) * n) << std::endl;
  for (const auto model :
       {ContactModel::frictionless, ContactModel::coulomb_friction})
    {
      Tensor<1, dim> velocities[2] = {v_a, v_b};
      const bool     corrected =
        ContactLaw<dim>::project_node({model, 0.5},
                                      {2, masses, rigid, normals, velocities});
      const bool unchanged =
        std::memcmp(&velocities[0], &v_a, sizeof(v_a)) == 0 &&
        std::memcmp(&velocities[1], &v_b, sizeof(v_b)) == 0;
      deallog << "  " << model_name(model) << ": returns "
              << (corrected ? "true" : "false")
              << ", velocities bit-for-bit unchanged: "
              << (unchanged ? "yes" : "no") << std::endl;
    }
}



// A deformable grain a against a rigid grain b.
template <int dim>
void
rigid_partner(const ContactModel    model,
              const double          mu,
              const Tensor<1, dim> &v_a)
{
  const Tensor<1, dim> n_a        = vec<dim>(1., 0., 0.);
  const Tensor<1, dim> v_rigid    = vec<dim>(0.5, -0.1, 0.2);
  const bool           rigid[2]   = {false, true};
  const Tensor<1, dim> normals[2] = {n_a, -n_a};
  deallog << model_name(model) << ", mu = " << mu << ", v_a = " << v_a
          << ", v_rigid = " << v_rigid << std::endl;

  Tensor<1, dim> results[2];
  bool           same_for_all_masses = true;
  for (const double rigid_mass : {7., 7e6, 0.})
    {
      const double   masses[2]     = {2., rigid_mass};
      Tensor<1, dim> velocities[2] = {v_a, v_rigid};
      const bool     corrected =
        ContactLaw<dim>::project_node({model, mu},
                                      {2, masses, rigid, normals, velocities});
      if (rigid_mass == 7.)
        {
          results[0] = velocities[0];
          results[1] = velocities[1];
          deallog << "  returns " << (corrected ? "true" : "false")
                  << ", v_a after = " << velocities[0] << std::endl;
          deallog << "  v_a . n_a - v_rigid . n_a = "
                  << filter_out_small_numbers((velocities[0] - v_rigid) * n_a)
                  << ", rigid velocity unchanged: "
                  << (std::memcmp(&velocities[1], &v_rigid, sizeof(v_rigid)) ==
                          0 ?
                        "yes" :
                        "no")
                  << std::endl;
        }
      else if (velocities[0] != results[0] || velocities[1] != results[1])
        same_for_all_masses = false;
    }
  deallog << "  independent of the rigid field's mass: "
          << (same_for_all_masses ? "yes" : "no") << std::endl;
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;

  Tensor<1, dim> n = vec<dim>(1., 2., -0.5);
  n /= n.norm();
  Tensor<1, dim> t = vec<dim>(2., -1., 0.);
  t /= t.norm();
  not_approaching<dim>("receding", n, -0.8 * n + 0.3 * t, 0.4 * n - 0.2 * t);
  not_approaching<dim>("receding, e_x",
                       vec<dim>(1., 0., 0.),
                       vec<dim>(-1., 0.3, 0.1),
                       vec<dim>(1., 0.1, -0.2));
  not_approaching<dim>("sliding only",
                       vec<dim>(1., 0., 0.),
                       vec<dim>(0.25, 1., 0.5),
                       vec<dim>(0.25, -1., 0.));

  // v_a - v_rigid = (1.5, 0.4, 0.2): D = 1.5, C = |(0.4, 0.2)|.
  const Tensor<1, dim> v_a = vec<dim>(2., 0.3, 0.4);
  rigid_partner<dim>(ContactModel::frictionless, 0., v_a);
  rigid_partner<dim>(ContactModel::coulomb_friction, 0.1, v_a);
  rigid_partner<dim>(ContactModel::coulomb_friction, 0.5, v_a);
  // Single-field model: the deformable material takes the rigid velocity.
  rigid_partner<dim>(ContactModel::none, 0., v_a);
  // Receding from the rigid grain.
  rigid_partner<dim>(ContactModel::coulomb_friction,
                     0.5,
                     vec<dim>(0.2, 0.3, 0.4));
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
