// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// SparseCholesky (the inverse of the 'sparse Cholesky' preconditioner):
// (1) on a symmetric positive definite matrix (a 1D Laplacian plus a mass)
// with one decoupled row, a light slot's m delta of tiny m, that the other
// rows couple to strongly (so the symmetric part of the whole matrix is
// indefinite), it solves A x = b to round-off: the decoupled row is solved
// first and moved to the right-hand side; (2) new values in the same pattern
// (the ordering kept) again to round-off; (3) with a non-symmetric part the
// solve inverts (A + A^T) / 2; (4) a matrix whose symmetric part is indefinite
// is reported (factorize() returns false) instead of giving nonsense; (5) a
// pattern flagged new that is the one analysed last keeps its analysis and
// solves to round-off after the failed factorisation; (6) it keeps OpenMP to
// one thread (grainmpm runs one thread per MPI process).

#include <grainmpm/solvers/sparse_cholesky.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <omp.h>

#include <cmath>
#include <vector>

#include "../tests.h"

using namespace grainmpm;

constexpr unsigned int n     = 40;
constexpr unsigned int light = 17;

// A of the test: (2 + mass) on the diagonal, -1 beside it, scaled by
// @p scale; row light is @p tiny delta, and rows light - 1 and light + 1
// couple to it by -@p coupling (and not to each other).
void
fill(TrilinosWrappers::SparseMatrix &A,
     const double                    scale,
     const double                    mass,
     const double                    tiny,
     const double                    coupling,
     const double                    skew)
{
  A = 0.;
  for (unsigned int i = 0; i < n; ++i)
    {
      if (i == light)
        {
          A.set(i, i, tiny);
          continue;
        }
      A.set(i, i, scale * (2. + mass));
      for (const int d : {-1, 1})
        {
          const int j = static_cast<int>(i) + d;
          if (j < 0 || j >= static_cast<int>(n))
            continue;
          if (static_cast<unsigned int>(j) == light)
            A.set(i, j, -coupling);
          else
            A.set(i, j, scale * (-1. + d * skew));
        }
    }
}



void
report(const std::string                    &name,
       const TrilinosWrappers::SparseMatrix &A,
       SparseCholesky                       &cholesky,
       const bool                            symmetric,
       const bool                            new_pattern)
{
  const bool ok = cholesky.factorize(A, new_pattern);
  deallog << name << ": factorised: " << (ok ? "yes" : "no");
  if (!ok)
    {
      deallog << std::endl;
      return;
    }
  // b = A x0, or b = S x0 with S the symmetric part on the coupled rows.
  std::vector<double> x0(n), b(n, 0.), x(n);
  for (unsigned int i = 0; i < n; ++i)
    x0[i] = std::sin(1. + 3. * i);
  for (unsigned int i = 0; i < n; ++i)
    for (auto entry = A.begin(i); entry != A.end(i); ++entry)
      {
        const unsigned int j = entry->column();
        double             a = entry->value();
        if (!symmetric && i != light && j != light)
          a = 0.5 * (a + A.el(j, i));
        b[i] += a * x0[j];
      }
  cholesky.solve(x.data(), b.data());
  double error = 0., norm = 0.;
  for (unsigned int i = 0; i < n; ++i)
    {
      error = std::max(error, std::abs(x[i] - x0[i]));
      norm  = std::max(norm, std::abs(x0[i]));
    }
  deallog << ", max |x - x0| / max |x0| < 1e-10: "
          << (error < 1e-10 * norm ? "yes" : "no") << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  DynamicSparsityPattern pattern(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i > 0 ? i - 1 : 0); j < std::min(n, i + 2); ++j)
      pattern.add(i, j);
  TrilinosWrappers::SparseMatrix A;
  A.reinit(complete_index_set(n),
           complete_index_set(n),
           pattern,
           MPI_COMM_WORLD);

  SparseCholesky cholesky;
  fill(A, 1., 0.1, 1e-9, 1., 0.);
  report("decoupled light row", A, cholesky, true, true);
  fill(A, 3., 0.5, 2e-9, 5., 0.);
  report("new values, same pattern", A, cholesky, true, false);
  fill(A, 1., 0.1, 1e-9, 1., 0.2);
  report("non-symmetric part", A, cholesky, false, false);
  fill(A, 1., -0.5, 1e-9, 1., 0.);
  report("indefinite", A, cholesky, true, true);
  fill(A, 2., 0.3, 1e-9, 1., 0.);
  report("same pattern flagged new (analysis kept)", A, cholesky, true, true);
  deallog << "size: " << cholesky.size() << std::endl;
  deallog << "active OpenMP levels at most: " << omp_get_max_active_levels()
          << std::endl;
}
