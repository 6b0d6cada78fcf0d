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
    constexpr unsigned int n_sums = 17;
    double values[n_sums] = {static_cast<double>(events.n_contact_nodes),
                             static_cast<double>(events.n_removed),
                             static_cast<double>(events.n_held_at_walls),
                             ledger.transfer_energy_change,
                             ledger.plastic_work,
                             ledger.friction_work,
                             ledger.boundary_work,
                             ledger.leapfrog_energy_change,
                             sums.kinetic_energy,
                             sums.elastic_energy,
                             sums.momentum[0],
                             sums.momentum[1],
                             sums.momentum[2],
                             sums.first_moment[0],
                             sums.first_moment[1],
                             sums.first_moment[2],
                             ledger.hypoelastic_correction};
    Utilities::MPI::sum(ArrayView<const double>(values, n_sums),
                        communicator,
                        ArrayView<double>(values, n_sums));
    events.n_contact_nodes = static_cast<unsigned int>(values[0]);
    events.n_removed       = static_cast<types::particle_index>(values[1]);
    events.n_held_at_walls = static_cast<types::particle_index>(values[2]);
    ledger.transfer_energy_change = values[3];
    ledger.plastic_work           = values[4];
    ledger.friction_work          = values[5];
    ledger.boundary_work          = values[6];
    ledger.leapfrog_energy_change = values[7];
    sums.kinetic_energy           = values[8];
    sums.elastic_energy           = values[9];
    ledger.hypoelastic_correction = values[16];
    for (unsigned int d = 0; d < 3; ++d)
      {
        sums.momentum[d]     = values[10 + d];
        sums.first_moment[d] = values[13 + d];
      }
    double maxima[2] = {events.max_speed, events.sorted ? 1. : 0.};
    Utilities::MPI::max(ArrayView<const double>(maxima, 2),
                        communicator,
                        ArrayView<double>(maxima, 2));
    events.max_speed = maxima[0];
    events.sorted    = maxima[1] > 0.;
  }
} // namespace grainmpm
