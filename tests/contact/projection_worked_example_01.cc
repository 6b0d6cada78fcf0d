// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// ContactLaw::project_node on a worked example (doc/theory.md section
// 5.2): two grains at one node, m_a = 1, v_a = (1, 0.2), n_a = (1, 0) and
// m_b = 3, v_b = (-1, 0), n_b = (-1, 0), so v_cm = (-0.5, 0.05). With
// mu = 0.05 both slip (D_a = 1.5, C_a = 0.15): v_a = (-0.5, 0.125),
// v_b = (-0.5, 0.025); with mu = 0.2 both stick at v_cm; frictionless,
// v_a = (-0.5, 0.2), v_b = (-0.5, 0). Momentum (-2, 0.2) is unchanged.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

void
run(const ContactModel model, const double mu)
{
  deallog << (model == ContactModel::frictionless ? "frictionless" :
                                                    "Coulomb friction")
          << ", mu = " << mu << std::endl;

  const double       masses[2]     = {1., 3.};
  const bool         rigid[2]      = {false, false};
  const Tensor<1, 2> normals[2]    = {Tensor<1, 2>({1., 0.}),
                                      Tensor<1, 2>({-1., 0.})};
  Tensor<1, 2>       velocities[2] = {Tensor<1, 2>({1., 0.2}),
                                      Tensor<1, 2>({-1., 0.})};
  const Tensor<1, 2> momentum_before =
    masses[0] * velocities[0] + masses[1] * velocities[1];
  const Tensor<1, 2> v_cm = momentum_before / (masses[0] + masses[1]);

  const bool corrected =
    ContactLaw<2>::project_node({model, mu},
                                {2, masses, rigid, normals, velocities});

  const Tensor<1, 2> momentum_after =
    masses[0] * velocities[0] + masses[1] * velocities[1];
  deallog << "corrected: " << (corrected ? "yes" : "no") << std::endl;
  deallog << "v_a = " << velocities[0] << ", v_b = " << velocities[1]
          << std::endl;
  deallog << "momentum before = " << momentum_before
          << ", after = " << momentum_after << std::endl;
  for (unsigned int g = 0; g < 2; ++g)
    {
      // Stick: no relative tangential velocity left.
      const Tensor<1, 2> relative = velocities[g] - v_cm;
      const double       tangential =
        (relative - (relative * normals[g]) * normals[g]).norm();
      deallog << "grain " << (g == 0 ? "a" : "b") << ": (v - v_cm) . n = "
              << filter_out_small_numbers(relative * normals[g]) << ", "
              << (tangential < 1e-12 ? "stick" : "slip") << std::endl;
    }
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  run(ContactModel::coulomb_friction, 0.05);
  run(ContactModel::coulomb_friction, 0.2);
  run(ContactModel::frictionless, 0.);
}
