// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A small replacement for deal.II's tests/tests.h (which the Debian package
// does not ship): deallog to the file "output", fixed number format, and a
// filter for round-off zeros.

#ifndef grainmpm_tests_tests_h
#define grainmpm_tests_tests_h

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <cmath>
#include <fstream>
#include <iomanip>

std::ofstream logfile("output");

inline void
initlog()
{
  dealii::deallog.attach(logfile);
  dealii::deallog.depth_console(0);
  logfile << std::setprecision(6);
  dealii::deallog << std::setprecision(6);
}

/**
 * initlog() for tests run on several MPI ranks: rank 0 writes the output,
 * the others write nothing.
 */
inline void
initlog_on_root(const MPI_Comm communicator = MPI_COMM_WORLD)
{
  if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
    initlog();
  else
    dealii::deallog.depth_console(0);
}

/** x, or zero if |x| < tolerance: round-off zeros print as 0. */
inline double
filter_out_small_numbers(const double x, const double tolerance = 1e-12)
{
  return std::abs(x) < tolerance ? 0. : x;
}

/**
 * Portable uniform random numbers in [0, 1): a 64-bit linear congruential
 * generator advancing @p state, the same on every platform.
 */
inline double
uniform_random(unsigned long long &state)
{
  state = 6364136223846793005ULL * state + 1442695040888963407ULL;
  return (state >> 11) * (1.0 / 9007199254740992.0);
}

/** A vector with components uniform in [-1, 1) from @p state. */
template <int dim>
dealii::Tensor<1, dim>
random_vector(unsigned long long &state)
{
  dealii::Tensor<1, dim> v;
  for (unsigned int d = 0; d < dim; ++d)
    v[d] = 2. * uniform_random(state) - 1.;
  return v;
}

/** A unit vector from random_vector() (rejecting lengths below 0.1). */
template <int dim>
dealii::Tensor<1, dim>
random_unit_vector(unsigned long long &state)
{
  dealii::Tensor<1, dim> v;
  do
    v = random_vector<dim>(state);
  while (v.norm() < 0.1);
  return v / v.norm();
}

#endif
