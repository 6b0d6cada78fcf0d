// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/step_statistics.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

namespace grainmpm
{
  void
  StepStatistics::reduce(const MPI_Comm communicator)
  {
    if (Utilities::MPI::n_mpi_processes(communicator) == 1)
      return;
    double sums[8] = {static_cast<double>(n_contact_nodes),
                      static_cast<double>(n_removed),
                      static_cast<double>(n_held_at_walls),
                      transfer_energy_change,
                      plastic_work,
                      friction_work,
                      boundary_work,
                      impact_loss};
    Utilities::MPI::sum(ArrayView<const double>(sums, 8),
                        communicator,
                        ArrayView<double>(sums, 8));
    n_contact_nodes        = static_cast<unsigned int>(sums[0]);
    n_removed              = static_cast<types::particle_index>(sums[1]);
    n_held_at_walls        = static_cast<types::particle_index>(sums[2]);
    transfer_energy_change = sums[3];
    plastic_work           = sums[4];
    friction_work          = sums[5];
    boundary_work          = sums[6];
    impact_loss            = sums[7];
    max_speed              = Utilities::MPI::max(max_speed, communicator);
    sorted = Utilities::MPI::max(sorted ? 1U : 0U, communicator) > 0;
  }
} // namespace grainmpm
