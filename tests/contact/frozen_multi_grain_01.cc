// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The contact law with frozen states (ContactLaw::project_node_frozen,
// what the implicit residual applies) against the law deciding the states
// (ContactLaw::project_node, what the explicit scheme applies), with the
// states the deciding law takes in its first pass at the same velocities:
// - two grains (antiparallel normals): the frozen law gives bit for bit
//   what the deciding law gives, satisfies the constraints and conserves
//   momentum;
// - three or four grains: the frozen law (one projection, one
//   momentum-restoring shift) conserves momentum to round-off and is
//   linear in the velocities, which the Jacobian-free Newton solve needs;
//   the shift leaves the constraints violated, and alternating projection
//   and shift until the shift vanishes (what the deciding law does) is no
//   option for the frozen law: with Coulomb friction it diverges at some
//   nodes of three grains in 2D (a violation of 3.6e5 after 1000 passes).

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

// One random sequence for the whole test.
unsigned long long random_state = 1234;

double
uniform()
{
  return uniform_random(random_state);
}



// Largest violation of the frozen constraints of @p states by @p v,
// relative to the centre-of-mass velocity.
template <int dim>
double
constraint_violation(const unsigned int    n,
                     const double         *masses,
                     const Tensor<1, dim> *normals,
                     const ContactState   *states,
                     const Tensor<1, dim> *slips,
                     const double          mu,
                     const Tensor<1, dim> *v)
{
  Tensor<1, dim> momentum;
  double         total = 0.;
  for (unsigned int k = 0; k < n; ++k)
    {
      momentum += masses[k] * v[k];
      total += masses[k];
    }
  const Tensor<1, dim> centre    = momentum / total;
  double               violation = 0.;
  for (unsigned int k = 0; k < n; ++k)
    if (states[k] == ContactState::sticking)
      violation = std::max(violation, (v[k] - centre).norm());
    else if (states[k] == ContactState::sliding)
      {
        // The frozen map is idempotent on a satisfied constraint.
        Tensor<1, dim> w = v[k];
        ContactLaw<dim>::apply_state(
          states[k], normals[k], mu, slips[k], centre, w);
        violation = std::max(violation, (w - v[k]).norm());
      }
  return violation;
}



template <int dim>
void
test(const ContactModel model, const unsigned int n_fields)
{
  deallog << n_fields << " grains, "
          << (model == ContactModel::frictionless ? "frictionless" :
                                                    "Coulomb friction")
          << std::endl;
  const double mu                 = 0.3;
  const bool   rigid[4]           = {false, false, false, false};
  double       max_momentum_error = 0., max_violation = 0.;
  double       max_linearity_error = 0., max_iterated_violation = 0.;
  unsigned int n_nodes_constrained = 0, n_bitwise_different = 0;
  for (unsigned int trial = 0; trial < 500; ++trial)
    {
      double         masses[4];
      Tensor<1, dim> normals[4], velocities[4];
      for (unsigned int k = 0; k < n_fields; ++k)
        {
          masses[k]     = 0.1 + 10. * uniform();
          normals[k]    = random_unit_vector<dim>(random_state);
          velocities[k] = random_vector<dim>(random_state);
        }
      // Two fields get antiparallel normals (GrainContact::compute_normals).
      if (n_fields == 2)
        normals[1] = -normals[0];

      // The states the deciding law takes at these velocities.
      Tensor<1, dim> decided[4], slips[4], reference;
      ContactState   states[4];
      for (unsigned int k = 0; k < n_fields; ++k)
        decided[k] = velocities[k];
      ContactNode<dim> node{n_fields, masses, rigid, normals, decided};
      node.states          = states;
      node.slip_directions = slips;
      node.reference       = &reference;
      const bool corrected = ContactLaw<dim>::project_node({model, mu}, node);
      if (!corrected)
        continue;
      ++n_nodes_constrained;

      // The frozen law on the same velocities.
      const auto frozen_law = [&](Tensor<1, dim> *x) {
        ContactLaw<dim>::project_node_frozen(
          {n_fields, masses, rigid, normals, x}, states, slips, mu);
      };
      Tensor<1, dim> frozen[4];
      for (unsigned int k = 0; k < n_fields; ++k)
        frozen[k] = velocities[k];
      frozen_law(frozen);

      Tensor<1, dim> momentum_before, momentum_after;
      double         scale = 0.;
      for (unsigned int k = 0; k < n_fields; ++k)
        {
          momentum_before += masses[k] * velocities[k];
          momentum_after += masses[k] * frozen[k];
          scale += masses[k] * velocities[k].norm();
        }
      max_momentum_error =
        std::max(max_momentum_error,
                 (momentum_after - momentum_before).norm() / scale);
      max_violation =
        std::max(max_violation,
                 constraint_violation<dim>(
                   n_fields, masses, normals, states, slips, mu, frozen));
      if (n_fields == 2)
        for (unsigned int k = 0; k < n_fields; ++k)
          if (frozen[k] != decided[k])
            ++n_bitwise_different;

      // Linear: the law at 2 v + w is 2 P(v) + P(w).
      Tensor<1, dim> w[4], combined[4];
      for (unsigned int k = 0; k < n_fields; ++k)
        {
          w[k]        = random_vector<dim>(random_state);
          combined[k] = 2. * velocities[k] + w[k];
        }
      for (Tensor<1, dim> *x : {w, combined})
        frozen_law(x);
      for (unsigned int k = 0; k < n_fields; ++k)
        max_linearity_error =
          std::max(max_linearity_error,
                   (combined[k] - 2. * frozen[k] - w[k]).norm());

      // The frozen law alternated with the shift: 1000 more passes.
      if (n_fields > 2)
        {
          for (unsigned int pass = 0; pass < 1000; ++pass)
            frozen_law(frozen);
          max_iterated_violation =
            std::max(max_iterated_violation,
                     constraint_violation<dim>(
                       n_fields, masses, normals, states, slips, mu, frozen));
        }
    }
  deallog << "  nodes with a constrained field: "
          << (n_nodes_constrained > 100 ? "more than 100" : "too few")
          << std::endl;
  deallog << "  momentum conserved to 1e-13: "
          << (max_momentum_error < 1e-13 ? "yes" : "no") << std::endl;
  if (n_fields == 2)
    deallog << "  frozen constraints satisfied to 1e-12: "
            << (max_violation < 1e-12 ? "yes" : "no") << std::endl;
  else
    deallog << "  frozen constraints violated by more than 1e-3 after the "
               "shift: "
            << (max_violation > 1e-3 ? "yes" : "no") << std::endl;
  deallog << "  linear in the velocities to 1e-12: "
          << (max_linearity_error < 1e-12 ? "yes" : "no") << std::endl;
  if (n_fields == 2)
    deallog << "  same bits as the deciding law: "
            << (n_bitwise_different == 0 ? "yes" : "no") << std::endl;
  else if (model == ContactModel::coulomb_friction && n_fields == 3)
    deallog << "  1000 alternations of frozen law and shift diverge (largest "
               "violation > 100): "
            << (max_iterated_violation > 100. ? "yes" : "no") << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  for (const ContactModel model :
       {ContactModel::frictionless, ContactModel::coulomb_friction})
    {
      test<2>(model, 2);
      test<2>(model, 3);
      test<3>(model, 4);
    }
}
