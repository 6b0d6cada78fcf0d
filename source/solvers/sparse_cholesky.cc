// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/solvers/sparse_cholesky.h>

#include <deal.II/base/exceptions.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace grainmpm
{
  namespace
  {
    /**
     * f(row, k, local column, value) for each stored entry of @p A, row by
     * row, k counting the entries (the rows of @p A are 0 to n - 1 in
     * order).
     */
    template <typename Function>
    void
    for_each_entry(const Epetra_CrsMatrix &A, const Function &f)
    {
      std::size_t k = 0;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          int     length;
          double *values;
          int    *columns;
          A.ExtractMyRowView(r, length, values, columns);
          for (int e = 0; e < length; ++e, ++k)
            f(r, k, columns[e], values[e]);
        }
    }
  } // namespace



  struct SparseCholesky::Data
  {
    cholmod_common common;
    /**
     * The lower triangle of P (A + A^T) / 2 P^T, P the fill-reducing
     * ordering, and its factor. The factor is analysed in the natural
     * order of this matrix, so that CHOLMOD factorises it as it is
     * instead of permuting (transposing) it at every factorisation.
     */
    cholmod_sparse *symmetric = nullptr;
    cholmod_factor *factor    = nullptr;
    std::size_t     n         = 0;
    /**
     * The pattern of A the analysis is for: the start of each row and the
     * global column of each stored entry, in row order.
     */
    std::vector<std::size_t> row_start;
    std::vector<int>         entry_columns;
    /** The ordering: row k of the permuted matrix is row order[k] of A. */
    std::vector<SuiteSparse_long> order;
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
    /** The right-hand side with the moved couplings, in the order of A. */
    mutable std::vector<double> moved_rhs;
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

    /**
     * The ordering, the pattern of symmetric, position, and the symbolic
     * analysis for the pattern of @p A, unless it is the pattern they are
     * for already.
     */
    void
    analyse(const Epetra_CrsMatrix &A);

    /**
     * The pattern of the triangle (stype 1: upper, -1: lower) of the
     * matrix with the entries (row, column) of A, row and column mapped
     * by @p map; with @p positions, each entry's place in it and zero
     * values.
     */
    cholmod_sparse *
    triangle(const std::function<SuiteSparse_long(int)> &map,
             const int                                   stype,
             std::vector<SuiteSparse_long>              *positions);
  };



  cholmod_sparse *
  SparseCholesky::Data::triangle(
    const std::function<SuiteSparse_long(int)> &map,
    const int                                   stype,
    std::vector<SuiteSparse_long>              *positions)
  {
    const std::size_t n_entries = entry_columns.size();
    cholmod_triplet  *triplets =
      cholmod_l_allocate_triplet(n,
                                 n,
                                 n_entries,
                                 stype,
                                 positions != nullptr ? CHOLMOD_REAL :
                                                        CHOLMOD_PATTERN,
                                 &common);
    AssertThrow(triplets != nullptr,
                ExcMessage("The sparse Cholesky factorisation ran out of "
                           "memory; set Linear solver/Preconditioner = AMG."));
    auto *const rows    = static_cast<SuiteSparse_long *>(triplets->i);
    auto *const columns = static_cast<SuiteSparse_long *>(triplets->j);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t k = row_start[r]; k < row_start[r + 1]; ++k)
        {
          const SuiteSparse_long i = map(r), j = map(entry_columns[k]);
          rows[k]    = stype > 0 ? std::min(i, j) : std::max(i, j);
          columns[k] = stype > 0 ? std::max(i, j) : std::min(i, j);
        }
    if (positions != nullptr)
      std::fill_n(static_cast<double *>(triplets->x), n_entries, 0.);
    triplets->nnz = n_entries;
    cholmod_sparse *matrix =
      cholmod_l_triplet_to_sparse(triplets, n_entries, &common);
    AssertThrow(matrix != nullptr,
                ExcMessage("The sparse Cholesky factorisation ran out of "
                           "memory; set Linear solver/Preconditioner = AMG."));
    cholmod_l_sort(matrix, &common);
    if (positions != nullptr)
      {
        const auto *const start = static_cast<SuiteSparse_long *>(matrix->p);
        const auto *const index = static_cast<SuiteSparse_long *>(matrix->i);
        positions->resize(n_entries);
        for (std::size_t k = 0; k < n_entries; ++k)
          (*positions)[k] = std::lower_bound(index + start[columns[k]],
                                             index + start[columns[k] + 1],
                                             rows[k]) -
                            index;
      }
    cholmod_l_free_triplet(&triplets, &common);
    return matrix;
  }



  void
  SparseCholesky::Data::analyse(const Epetra_CrsMatrix &A)
  {
    AssertThrow(A.RowMap().LinearMap() && A.RowMap().MinMyGID() == 0,
                ExcMessage("The rows must be in their global order."));
    // The pattern of A; the analysis of the pattern analysed last is kept.
    std::vector<std::size_t> new_row_start(A.NumMyRows() + 1, 0);
    std::vector<int>         new_columns(A.NumMyNonzeros());
    for_each_entry(
      A, [&](const int r, const std::size_t k, const int column, const double) {
        new_columns[k]       = A.ColMap().GID(column);
        new_row_start[r + 1] = k + 1;
      });
    for (int r = 0; r < A.NumMyRows(); ++r)
      new_row_start[r + 1] = std::max(new_row_start[r + 1], new_row_start[r]);
    if (factor != nullptr && new_row_start == row_start &&
        new_columns == entry_columns)
      return;
    row_start.swap(new_row_start);
    entry_columns.swap(new_columns);
    n = A.NumGlobalRows();
    cholmod_l_free_sparse(&symmetric, &common);
    cholmod_l_free_factor(&factor, &common);

    // The fill-reducing ordering of the pattern of A + A^T.
    {
      cholmod_sparse *upper =
        triangle([](const int i) { return i; }, 1, nullptr);
      cholmod_factor *ordered = cholmod_l_analyze(upper, &common);
      cholmod_l_free_sparse(&upper, &common);
      AssertThrow(ordered != nullptr,
                  ExcMessage("The sparse Cholesky analysis failed (CHOLMOD "
                             "status " +
                             std::to_string(common.status) +
                             "); set Linear solver/Preconditioner = AMG."));
      const auto *const perm = static_cast<SuiteSparse_long *>(ordered->Perm);
      order.assign(perm, perm + n);
      cholmod_l_free_factor(&ordered, &common);
    }
    std::vector<SuiteSparse_long> place(n);
    for (std::size_t k = 0; k < n; ++k)
      place[order[k]] = k;

    // The permuted matrix, analysed in its own order: the ordering above
    // is postordered already.
    symmetric = triangle([&](const int i) { return place[i]; }, -1, &position);
    common.method[0].ordering = CHOLMOD_NATURAL;
    common.postorder          = false;
    factor                    = cholmod_l_analyze(symmetric, &common);
    common.method[0].ordering = CHOLMOD_METIS;
    common.postorder          = true;
    AssertThrow(factor != nullptr && factor->ordering == CHOLMOD_NATURAL,
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
        data->entry_columns.size() !=
          static_cast<std::size_t>(A.NumMyNonzeros()))
      data->analyse(A);
    const std::vector<int> &columns = data->entry_columns;

    // Rows without off-diagonal values are decoupled.
    const std::size_t  n         = data->n;
    std::vector<bool> &decoupled = data->decoupled;
    decoupled.assign(n, true);
    data->diagonal.assign(n, 0.);
    for_each_entry(
      A, [&](const int i, const std::size_t k, const int, const double value) {
        if (i == columns[k])
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
    for_each_entry(
      A, [&](const int i, const std::size_t k, const int, const double value) {
        const int j = columns[k];
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
    // couplings to these x_j to the right-hand side. The factor is that of
    // the permuted matrix: b and x are permuted here.
    std::vector<double> &moved = data->moved_rhs;
    moved.assign(b, b + data->n);
    for (std::size_t k = 0; k < data->moved_values.size(); ++k)
      {
        const auto j = data->moved_columns[k];
        moved[data->moved_rows[k]] -=
          data->moved_values[k] * b[j] / data->diagonal[j];
      }
    auto *const rhs = static_cast<double *>(data->rhs->x);
    for (std::size_t k = 0; k < data->n; ++k)
      rhs[k] = moved[data->order[k]];
    cholmod_l_solve2(CHOLMOD_A,
                     data->factor,
                     data->rhs,
                     nullptr,
                     &data->solution,
                     nullptr,
                     &data->workspace,
                     &data->extra,
                     &data->common);
    const auto *const solution = static_cast<double *>(data->solution->x);
    for (std::size_t k = 0; k < data->n; ++k)
      x[data->order[k]] = solution[k];
  }
} // namespace grainmpm
