// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/solvers/sparse_cholesky.h>

#include <deal.II/base/exceptions.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace grainmpm
{
  namespace
  {
    /**
     * f(row, column, value) for each stored entry of @p A, row by row, in
     * global numbers (the rows of @p A are 0 to n - 1 in order).
     */
    template <typename Function>
    void
    for_each_entry(const Epetra_CrsMatrix &A, const Function &f)
    {
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          int     length;
          double *values;
          int    *columns;
          A.ExtractMyRowView(r, length, values, columns);
          for (int e = 0; e < length; ++e)
            f(r, A.ColMap().GID(columns[e]), values[e]);
        }
    }
  } // namespace



  struct SparseCholesky::Data
  {
    cholmod_common common;
    /** The upper triangle of (A + A^T) / 2 and its factor. */
    cholmod_sparse *symmetric = nullptr;
    cholmod_factor *factor    = nullptr;
    std::size_t     n         = 0;
    /** Entries of A the pattern was built for. */
    std::size_t n_entries = 0;
    /** For each stored entry of A, in row order, its place in symmetric. */
    std::vector<SuiteSparse_long> position;
    /**
     * Rows without off-diagonal values, the diagonal of A, and the other
     * rows' values in the columns of those rows (row, column, value),
     * which solve() moves to the right-hand side.
     */
    std::vector<bool>   decoupled;
    std::vector<double> diagonal;
    std::vector<int>    moved_rows;
    std::vector<int>    moved_columns;
    std::vector<double> moved_values;
    /** Right-hand side and workspaces of cholmod_l_solve2(). */
    cholmod_dense *rhs       = nullptr;
    cholmod_dense *solution  = nullptr;
    cholmod_dense *workspace = nullptr;
    cholmod_dense *extra     = nullptr;

    Data()
    {
      cholmod_l_start(&common);
      // Failures are reported through the status, not printed.
      common.print = 0;
      // L L^T always (CHOLMOD takes L D L^T for small matrices, which does
      // not detect an indefinite matrix), and nested dissection (METIS):
      // about 40 % fewer operations than AMD on a packing of disks.
      common.supernodal         = CHOLMOD_SUPERNODAL;
      common.nmethods           = 1;
      common.method[0].ordering = CHOLMOD_METIS;
      // CHOLMOD's OpenMP regions start threads of their own whatever the
      // cores and the MPI processes on them; grainmpm runs one thread per
      // MPI process (main.cc), so the regions run on one (no level of
      // parallelism is active).
      omp_set_max_active_levels(0);
    }

    ~Data()
    {
      cholmod_l_free_sparse(&symmetric, &common);
      cholmod_l_free_factor(&factor, &common);
      cholmod_l_free_dense(&rhs, &common);
      cholmod_l_free_dense(&solution, &common);
      cholmod_l_free_dense(&workspace, &common);
      cholmod_l_free_dense(&extra, &common);
      cholmod_l_finish(&common);
    }

    /** The pattern of symmetric, position, and the symbolic analysis. */
    void
    analyse(const Epetra_CrsMatrix &A);
  };



  void
  SparseCholesky::Data::analyse(const Epetra_CrsMatrix &A)
  {
    cholmod_l_free_sparse(&symmetric, &common);
    cholmod_l_free_factor(&factor, &common);
    AssertThrow(A.RowMap().LinearMap() && A.RowMap().MinMyGID() == 0,
                ExcMessage("The rows must be in their global order."));
    n         = A.NumGlobalRows();
    n_entries = A.NumMyNonzeros();
    cholmod_triplet *triplets =
      cholmod_l_allocate_triplet(n, n, n_entries, 1, CHOLMOD_REAL, &common);
    AssertThrow(triplets != nullptr,
                ExcMessage("The sparse Cholesky factorisation ran out of "
                           "memory; set Linear solver/Preconditioner = AMG."));
    auto *const rows    = static_cast<SuiteSparse_long *>(triplets->i);
    auto *const columns = static_cast<SuiteSparse_long *>(triplets->j);
    auto *const values  = static_cast<double *>(triplets->x);
    std::size_t k       = 0;
    for_each_entry(A, [&](const int i, const int j, const double) {
      rows[k]    = std::min(i, j);
      columns[k] = std::max(i, j);
      values[k]  = 0.;
      ++k;
    });
    triplets->nnz = k;
    symmetric     = cholmod_l_triplet_to_sparse(triplets, k, &common);
    AssertThrow(symmetric != nullptr,
                ExcMessage("The sparse Cholesky factorisation ran out of "
                           "memory; set Linear solver/Preconditioner = AMG."));
    cholmod_l_sort(symmetric, &common);

    const auto *const start = static_cast<SuiteSparse_long *>(symmetric->p);
    const auto *const index = static_cast<SuiteSparse_long *>(symmetric->i);
    position.resize(k);
    for (std::size_t e = 0; e < k; ++e)
      position[e] = std::lower_bound(index + start[columns[e]],
                                     index + start[columns[e] + 1],
                                     rows[e]) -
                    index;
    cholmod_l_free_triplet(&triplets, &common);

    factor = cholmod_l_analyze(symmetric, &common);
    AssertThrow(factor != nullptr,
                ExcMessage("The sparse Cholesky analysis failed (CHOLMOD "
                           "status " +
                           std::to_string(common.status) +
                           "); set Linear solver/Preconditioner = AMG."));
    cholmod_l_free_dense(&rhs, &common);
    rhs = cholmod_l_zeros(n, 1, CHOLMOD_REAL, &common);
  }



  SparseCholesky::SparseCholesky()
    : data(std::make_unique<Data>())
  {}



  SparseCholesky::~SparseCholesky() = default;



  std::size_t
  SparseCholesky::size() const
  {
    return data->n;
  }



  bool
  SparseCholesky::factorize(const TrilinosWrappers::SparseMatrix &matrix,
                            const bool                            new_pattern)
  {
    const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
    AssertThrow(A.NumMyRows() == A.NumGlobalRows(),
                ExcMessage("The sparse Cholesky factorisation needs the whole "
                           "matrix on one MPI process."));
    if (new_pattern || data->factor == nullptr ||
        data->n != static_cast<std::size_t>(A.NumGlobalRows()) ||
        data->n_entries != static_cast<std::size_t>(A.NumMyNonzeros()))
      data->analyse(A);

    // Rows without off-diagonal values are decoupled.
    const std::size_t  n         = data->n;
    std::vector<bool> &decoupled = data->decoupled;
    decoupled.assign(n, true);
    data->diagonal.assign(n, 0.);
    for_each_entry(A, [&](const int i, const int j, const double value) {
      if (i == j)
        data->diagonal[i] = value;
      else if (value != 0.)
        decoupled[i] = false;
    });

    // The values of (A + A^T) / 2 without the couplings of decoupled rows
    // and columns; those of the other rows go to the right-hand side.
    auto *const values = static_cast<double *>(data->symmetric->x);
    std::fill(values,
              values + static_cast<SuiteSparse_long *>(data->symmetric->p)[n],
              0.);
    data->moved_rows.clear();
    data->moved_columns.clear();
    data->moved_values.clear();
    std::size_t k = 0;
    for_each_entry(A, [&](const int i, const int j, const double value) {
      if (i == j)
        values[data->position[k]] += value;
      else if (!decoupled[i] && !decoupled[j])
        values[data->position[k]] += 0.5 * value;
      else if (decoupled[j] && value != 0.)
        {
          data->moved_rows.push_back(i);
          data->moved_columns.push_back(j);
          data->moved_values.push_back(value);
        }
      ++k;
    });

    cholmod_common &c = data->common;
    cholmod_l_factorize(data->symmetric, data->factor, &c);
    if (c.status == CHOLMOD_NOT_POSDEF)
      return false;
    AssertThrow(c.status == CHOLMOD_OK,
                ExcMessage("The sparse Cholesky factorisation failed (CHOLMOD "
                           "status " +
                           std::to_string(c.status) +
                           ", -2 is out of memory); set Linear "
                           "solver/Preconditioner = AMG."));
    return true;
  }



  void
  SparseCholesky::solve(double *x, const double *b) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    // A decoupled row j gives x_j = b_j / a_jj (the factor holds a_jj
    // there, so the solve below gives it back); the other rows move their
    // couplings to these x_j to the right-hand side.
    auto *const rhs = static_cast<double *>(data->rhs->x);
    std::memcpy(rhs, b, data->n * sizeof(double));
    for (std::size_t k = 0; k < data->moved_values.size(); ++k)
      {
        const auto j = data->moved_columns[k];
        rhs[data->moved_rows[k]] -=
          data->moved_values[k] * b[j] / data->diagonal[j];
      }
    cholmod_l_solve2(CHOLMOD_A,
                     data->factor,
                     data->rhs,
                     nullptr,
                     &data->solution,
                     nullptr,
                     &data->workspace,
                     &data->extra,
                     &data->common);
    std::memcpy(x, data->solution->x, data->n * sizeof(double));
  }
} // namespace grainmpm
