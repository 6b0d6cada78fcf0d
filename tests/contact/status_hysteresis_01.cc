// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// ContactLaw::classify with the hysteresis band of Nonlinear solver/
// Contact status tolerance: normal n = (1, 0), friction 0.5, band 0.1. A
// slot that was free is caught only beyond the band of approach, one that
// was held is released only beyond the band of separation; stick and slip
// change only beyond the band as well; without a band (or a previous state
// of a first decision) the plain contact law of Bardenhagen et al. 2001.

#include <grainmpm/contact/contact_law.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

#include "contact_tests.h"

using namespace grainmpm;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const Tensor<1, 2> normal({1., 0.});
  const double       mu = 0.5, band = 0.1;
  Tensor<1, 2>       slip;
  const auto         classify = [&](const double       approach,
                            const double       tangential,
                            const ContactState previous,
                            const double       b) {
    return state_name(ContactLaw<2>::classify(
      Tensor<1, 2>({approach, tangential}), normal, mu, slip, 0., previous, b));
  };

  deallog << "normal approach D (no tangential motion):" << std::endl;
  for (const double d : {-0.2, -0.05, 0.05, 0.2})
    deallog << "  D = " << d << ": no band "
            << classify(d, 0., ContactState::free, 0.) << ", was free "
            << classify(d, 0., ContactState::free, band) << ", was sticking "
            << classify(d, 0., ContactState::sticking, band) << std::endl;

  // D = 1: mu D = 0.5; slip speeds about it.
  deallog << "approach 1, tangential speed v_t (mu D = 0.5):" << std::endl;
  for (const double vt : {0.35, 0.45, 0.55, 0.65})
    deallog << "  v_t = " << vt << ": no band "
            << classify(1., vt, ContactState::free, 0.) << ", was sticking "
            << classify(1., vt, ContactState::sticking, band)
            << ", was sliding " << classify(1., vt, ContactState::sliding, band)
            << std::endl;
}
