// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_solvers_sparse_cholesky_h
#define grainmpm_solvers_sparse_cholesky_h

#include <grainmpm/base/config.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <memory>

namespace grainmpm
{
  /**
   * A sparse Cholesky factorisation L L^T of the symmetric part
   * (A + A^T) / 2 of a matrix held on one MPI process (CHOLMOD of
   * SuiteSparse, supernodal, nested-dissection ordering). The symbolic
   * analysis is kept for later factorisations of matrices with the same
   * sparsity pattern, so that a new contact status costs only the
   * numerical factorisation.
   */
  class SparseCholesky
  {
  public:
    SparseCholesky();

    ~SparseCholesky();

    SparseCholesky(const SparseCholesky &) = delete;

    SparseCholesky &
    operator=(const SparseCholesky &) = delete;

    /**
     * Factorise the symmetric part of @p matrix, whose rows must all be
     * owned by this process, in their global order. Rows without
     * off-diagonal values are decoupled: solve() gives them b_i / a_ii and
     * moves the other rows' couplings to them to the right-hand side (an
     * exact block-triangular solve), so that they do not enter the
     * symmetric part. Unless @p new_pattern, the sparsity pattern of
     * @p matrix is that of the last call and its ordering and symbolic
     * analysis are reused. Returns false if the symmetric part is not
     * positive definite; throws if CHOLMOD fails otherwise (out of memory).
     */
    bool
    factorize(const TrilinosWrappers::SparseMatrix &matrix,
              const bool                            new_pattern);

    /**
     * x = (L L^T)^-1 b for vectors of the matrix's size (plain arrays in
     * the row order of the matrix); @p x and @p b may not overlap.
     */
    void
    solve(double *x, const double *b) const;

    /** The size of the last factorised matrix (0 before). */
    std::size_t
    size() const;

  private:
    struct Data;
    std::unique_ptr<Data> data;
  };
} // namespace grainmpm

#endif
