// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// ContactLaw::project_node on random nodes (doc/theory.md section 5.2):
// momentum is conserved for two grains with antiparallel normals
// and for three grains, approaching grains end with no normal relative
// velocity (two grains), Coulomb friction sticks iff mu D >= C and
// otherwise reduces the slip by exactly mu D, receding grains are left
// untouched.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

// One random sequence for the whole test.
unsigned long long random_state = 2026;

double
uniform()
{
  return uniform_random(random_state);
}



template <int dim>
void
test_two_grains(const ContactModel model)
{
  deallog << "2 grains, "
          << (model == ContactModel::frictionless ? "frictionless" :
                                                    "Coulomb friction")
          << std::endl;
  const bool   rigid[2]             = {false, false};
  double       max_momentum_error   = 0.;
  double       max_normal_velocity  = 0.;
  double       max_friction_error   = 0.;
  unsigned int n_approaching        = 0;
  unsigned int n_stick              = 0;
  unsigned int n_slip               = 0;
  unsigned int n_wrong_decision     = 0;
  unsigned int n_receding_changed   = 0;
  unsigned int n_wrong_return_value = 0;
  for (unsigned int trial = 0; trial < 1000; ++trial)
    {
      const double masses[2] = {0.1 + 10. * uniform(), 0.1 + 10. * uniform()};
      const Tensor<1, dim> n = random_unit_vector<dim>(random_state);
      const Tensor<1, dim> normals[2]    = {n, -n};
      Tensor<1, dim>       velocities[2] = {random_vector<dim>(random_state),
                                            random_vector<dim>(random_state)};
      const double         mu            = 0.6 * uniform();
      const Tensor<1, dim> before[2]     = {velocities[0], velocities[1]};

      const Tensor<1, dim> momentum_before =
        masses[0] * velocities[0] + masses[1] * velocities[1];
      const double scale =
        masses[0] * velocities[0].norm() + masses[1] * velocities[1].norm();
      const Tensor<1, dim> v_cm = momentum_before / (masses[0] + masses[1]);
      double               D[2], C[2];
      for (unsigned int g = 0; g < 2; ++g)
        {
          const Tensor<1, dim> relative = velocities[g] - v_cm;
          D[g]                          = relative * normals[g];
          C[g]                          = (relative - D[g] * normals[g]).norm();
        }

      const bool corrected =
        ContactLaw<dim>::project_node({model, mu},
                                      {2, masses, rigid, normals, velocities});

      const Tensor<1, dim> momentum_after =
        masses[0] * velocities[0] + masses[1] * velocities[1];
      max_momentum_error =
        std::max(max_momentum_error,
                 (momentum_after - momentum_before).norm() / scale);
      if (corrected != (D[0] > 0. || D[1] > 0.))
        ++n_wrong_return_value;

      for (unsigned int g = 0; g < 2; ++g)
        {
          if (!(D[g] > 0.))
            {
              if (velocities[g] != before[g])
                ++n_receding_changed;
              continue;
            }
          ++n_approaching;
          const Tensor<1, dim> relative = velocities[g] - v_cm;
          const double         normal   = relative * normals[g];
          max_normal_velocity =
            std::max(max_normal_velocity, std::abs(normal) / scale);
          if (model == ContactModel::coulomb_friction)
            {
              const double slip_after = (relative - normal * normals[g]).norm();
              const bool   stick_expected = (mu * D[g] >= C[g]);
              // Stick: no slip left; slip: the slip reduced by mu D.
              const double expected = stick_expected ? 0. : C[g] - mu * D[g];
              max_friction_error =
                std::max(max_friction_error,
                         std::abs(slip_after - expected) / scale);
              if (stick_expected)
                ++n_stick;
              else
                ++n_slip;
              if ((slip_after < 1e-12 * scale) != stick_expected)
                ++n_wrong_decision;
            }
        }
    }
  deallog << "max |momentum after - before| / sum m |v| = "
          << filter_out_small_numbers(max_momentum_error) << std::endl;
  deallog << "approaching fields: " << n_approaching
          << ", max |(v_g - v_cm) . n_g| after / scale = "
          << filter_out_small_numbers(max_normal_velocity) << std::endl;
  deallog << "receding fields changed: " << n_receding_changed
          << ", wrong return values: " << n_wrong_return_value << std::endl;
  if (model == ContactModel::coulomb_friction)
    deallog << "stick (mu D >= C): " << n_stick << ", slip: " << n_slip
            << ", outcomes contradicting mu D >= C: " << n_wrong_decision
            << ", max |slip after - max(C - mu D, 0)| / scale = "
            << filter_out_small_numbers(max_friction_error) << std::endl;
}



template <int dim>
void
test_three_grains(const ContactModel model)
{
  deallog << "3 grains, "
          << (model == ContactModel::frictionless ? "frictionless" :
                                                    "Coulomb friction")
          << std::endl;
  const bool   rigid[3]             = {false, false, false};
  double       max_momentum_error   = 0.;
  double       max_relative_error   = 0.;
  double       max_approach_after   = 0.;
  unsigned int n_corrected          = 0;
  unsigned int n_approaching_before = 0;
  unsigned int n_still_approaching  = 0;
  for (unsigned int trial = 0; trial < 1000; ++trial)
    {
      const double masses[3] = {0.1 + 10. * uniform(),
                                0.1 + 10. * uniform(),
                                0.1 + 10. * uniform()};
      // Normals as GrainContact::compute_normals makes them from the mass
      // gradients g_g: n_g = (2 g_g - sum_k g_k) / |...|.
      const Tensor<1, dim> gradients[3] = {random_vector<dim>(random_state),
                                           random_vector<dim>(random_state),
                                           random_vector<dim>(random_state)};
      Tensor<1, dim>       normals[3];
      for (unsigned int g = 0; g < 3; ++g)
        {
          normals[g] =
            2. * gradients[g] - (gradients[0] + gradients[1] + gradients[2]);
          normals[g] /= normals[g].norm();
        }
      Tensor<1, dim> velocities[3] = {random_vector<dim>(random_state),
                                      random_vector<dim>(random_state),
                                      random_vector<dim>(random_state)};
      const double   mu            = 0.6 * uniform();

      Tensor<1, dim> momentum_before;
      double         scale = 0., total_mass = 0.;
      for (unsigned int g = 0; g < 3; ++g)
        {
          momentum_before += masses[g] * velocities[g];
          scale += masses[g] * velocities[g].norm();
          total_mass += masses[g];
        }
      const Tensor<1, dim> v_cm = momentum_before / total_mass;

      const Tensor<1, dim> initial_velocities[3] = {velocities[0],
                                                    velocities[1],
                                                    velocities[2]};
      double               approach_before[3];
      for (unsigned int g = 0; g < 3; ++g)
        approach_before[g] = (velocities[g] - v_cm) * normals[g];

      if (ContactLaw<dim>::project_node(
            {model, mu}, {3, masses, rigid, normals, velocities}))
        ++n_corrected;

      Tensor<1, dim> momentum_after;
      for (unsigned int g = 0; g < 3; ++g)
        momentum_after += masses[g] * velocities[g];
      max_momentum_error =
        std::max(max_momentum_error,
                 (momentum_after - momentum_before).norm() / scale);
      // Contact never creates kinetic energy at the node.
      double energy_before = 0., energy_after = 0.;
      for (unsigned int g = 0; g < 3; ++g)
        {
          energy_before +=
            0.5 * masses[g] * initial_velocities[g].norm_square();
          energy_after += 0.5 * masses[g] * velocities[g].norm_square();
        }
      max_relative_error = std::max(max_relative_error,
                                    (energy_after - energy_before) /
                                      std::max(energy_before, 1e-300));
      // Projection and momentum restoration alternate until no field
      // approaches: measure how much approach speed is left.
      for (unsigned int g = 0; g < 3; ++g)
        {
          const double approach = (velocities[g] - v_cm) * normals[g];
          if (approach_before[g] > 0.)
            ++n_approaching_before;
          if (approach_before[g] > 0.)
            max_approach_after =
              std::max(max_approach_after, approach * total_mass / scale);
          if (approach > 1e-12 * scale / total_mass)
            ++n_still_approaching;
        }
    }
  deallog << "nodes corrected: " << n_corrected
          << ", max |momentum after - before| / sum m |v| = "
          << filter_out_small_numbers(max_momentum_error) << std::endl;
  deallog << "max kinetic energy created at a node / kinetic energy = "
          << filter_out_small_numbers(std::max(max_relative_error, 0.))
          << std::endl;
  deallog << "fields approaching before the projection: "
          << n_approaching_before << ", after: " << n_still_approaching
          << ", max (v_g - v_cm) . n_g after / scale = " << max_approach_after
          << std::endl;
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  test_two_grains<dim>(ContactModel::frictionless);
  test_two_grains<dim>(ContactModel::coulomb_friction);
  test_three_grains<dim>(ContactModel::frictionless);
  test_three_grains<dim>(ContactModel::coulomb_friction);
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
