// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_mpi_tools_h
#define grainmpm_base_mpi_tools_h

#include <deal.II/base/mpi.h>

namespace grainmpm
{
  /**
   * The sum of @p value over the ranks of @p communicator below this one
   * (0 on rank 0): where this rank's share of a global numbering starts.
   * Collective.
   */
  template <typename T>
  T
  sum_over_lower_ranks(const T value, const MPI_Comm communicator)
  {
    T sum = 0;
    MPI_Exscan(&value,
               &sum,
               1,
               dealii::Utilities::MPI::mpi_type_id_for_type<T>,
               MPI_SUM,
               communicator);
    // MPI_Exscan leaves rank 0's result undefined.
    return dealii::Utilities::MPI::this_mpi_process(communicator) == 0 ? T(0) :
                                                                         sum;
  }
} // namespace grainmpm

#endif
