// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_input_record_h
#define grainmpm_postprocess_input_record_h

#include <grainmpm/base/parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <string>

namespace grainmpm
{
  /**
   * Record the inputs of a run in its `Output/Output directory` (made if
   * needed) before anything can fail: original.prm (the input file
   * @p input_file with its included files expanded, so that it runs again
   * as it is; original.json or original.xml for those formats),
   * parameters.prm and parameters.json (every value of @p prm, defaults
   * included) and, for a random packing, packing.csv (the grains it made,
   * as a grain list file). Rank 0 writes; an error (the directory cannot be
   * made, a file cannot be written) stops every rank with an InputError
   * naming the directory. Collective.
   */
  template <int dim>
  void
  record_inputs(const Parameters<dim>  &parameters,
                const ParameterHandler &prm,
                const std::string      &input_file,
                const MPI_Comm          communicator);
} // namespace grainmpm

#endif
