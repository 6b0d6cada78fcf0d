// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// ContactLaw::apply_wall (doc/theory.md section 6.1): free slip removes
// only an approaching normal component, friction sticks iff mu D >= C and
// otherwise reduces the slip by mu D, no slip zeroes the velocity, open
// does nothing; checked on every face of the box.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

template <int dim>
void
check(const BoundaryCondition &condition,
      const Tensor<1, dim>    &normal,
      const Tensor<1, dim>    &velocity,
      double                  &max_error)
{
  Tensor<1, dim> result = velocity;
  ContactLaw<dim>::apply_wall(condition, normal, result);

  // The expected velocity, from the formulas.
  const double         D       = velocity * normal;
  const Tensor<1, dim> tangent = velocity - D * normal;
  const double         C       = tangent.norm();
  Tensor<1, dim>       expected;
  switch (condition.type)
    {
      case BoundaryType::open:
        expected = velocity;
        break;
      case BoundaryType::no_slip:
        break;
      case BoundaryType::free_slip:
        expected = (D > 0. ? tangent : velocity);
        break;
      case BoundaryType::friction:
        if (!(D > 0.))
          expected = velocity;
        else if (condition.friction_coefficient * D >= C)
          expected = Tensor<1, dim>(); // stick to the wall
        else
          expected = (1. - condition.friction_coefficient * D / C) * tangent;
        break;
    }
  max_error = std::max(max_error, (result - expected).norm());
}



template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;

  std::vector<std::pair<std::string, BoundaryCondition>> conditions(5);
  conditions[0].first                       = "free slip";
  conditions[1].first                       = "friction 0.3";
  conditions[1].second.type                 = BoundaryType::friction;
  conditions[1].second.friction_coefficient = 0.3;
  conditions[2].first                       = "friction 0";
  conditions[2].second.type                 = BoundaryType::friction;
  conditions[3].first                       = "no slip";
  conditions[3].second.type                 = BoundaryType::no_slip;
  conditions[4].first                       = "open";
  conditions[4].second.type                 = BoundaryType::open;

  // On the x+ face (outward normal e_x): a velocity (v_n, v_t).
  Tensor<1, dim> normal;
  normal[0]                                               = 1.;
  const std::vector<std::pair<double, double>> velocities = {
    {1., 0.2},  // approaching; friction 0.3: mu D = 0.3 >= 0.2, stick
    {1., 0.5},  // approaching; friction 0.3: slip, v_t -> 0.2
    {-1., 0.5}, // receding
    {0., 0.5}}; // sliding along the wall
  for (const auto &condition : conditions)
    for (const auto &v : velocities)
      {
        Tensor<1, dim> velocity;
        velocity[0] = v.first;
        velocity[1] = v.second;
        ContactLaw<dim>::apply_wall(condition.second, normal, velocity);
        deallog << condition.first << ", v = (" << v.first << ", " << v.second
                << ") -> " << velocity << std::endl;
      }

  // Every face, many velocities, against the formulas.
  double error = 0.;
  for (unsigned int face = 0; face < 2 * dim; ++face)
    {
      Tensor<1, dim> face_normal;
      face_normal[face / 2] = (face % 2 == 0 ? -1. : 1.);
      for (const auto &condition : conditions)
        for (unsigned int k = 0; k < 50; ++k)
          {
            Tensor<1, dim> velocity;
            for (unsigned int d = 0; d < dim; ++d)
              velocity[d] = std::sin(1.7 * k + 2.3 * d + 0.9 * face);
            check<dim>(condition.second, face_normal, velocity, error);
          }
    }
  deallog << "all faces: max |apply_wall - formula| = "
          << filter_out_small_numbers(error) << std::endl;
}



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  test<2>();
  test<3>();
}
