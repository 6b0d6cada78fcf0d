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
    constexpr unsigned int n_sums       = 16;
    double                 sums[n_sums] = {static_cast<double>(n_contact_nodes),
                                           static_cast<double>(n_removed),
                                           static_cast<double>(n_held_at_walls),
                                           transfer_energy_change,
                                           plastic_work,
                                           friction_work,
                                           boundary_work,
                                           leapfrog_energy_change,
                                           kinetic_energy,
                                           elastic_energy,
                                           momentum[0],
                                           momentum[1],
                                           momentum[2],
                                           first_moment[0],
                                           first_moment[1],
                                           first_moment[2]};
    Utilities::MPI::sum(ArrayView<const double>(sums, n_sums),
                        communicator,
                        ArrayView<double>(sums, n_sums));
    n_contact_nodes        = static_cast<unsigned int>(sums[0]);
    n_removed              = static_cast<types::particle_index>(sums[1]);
    n_held_at_walls        = static_cast<types::particle_index>(sums[2]);
    transfer_energy_change = sums[3];
    plastic_work           = sums[4];
    friction_work          = sums[5];
    boundary_work          = sums[6];
    leapfrog_energy_change = sums[7];
    kinetic_energy         = sums[8];
    elastic_energy         = sums[9];
    for (unsigned int d = 0; d < 3; ++d)
      {
        momentum[d]     = sums[10 + d];
        first_moment[d] = sums[13 + d];
      }
    double maxima[2] = {max_speed, sorted ? 1. : 0.};
    Utilities::MPI::max(ArrayView<const double>(maxima, 2),
                        communicator,
                        ArrayView<double>(maxima, 2));
    max_speed = maxima[0];
    sorted    = maxima[1] > 0.;
  }
} // namespace grainmpm
