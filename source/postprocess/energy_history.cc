// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/energy_history.h>
#include <grainmpm/postprocess/history_file.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <iomanip>

namespace grainmpm
{
  template <int dim>
  EnergyHistory<dim>::EnergyHistory(
    const std::string                                          &filename,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
    const Tensor<1, dim>                                       &gravity,
    const MPI_Comm                                              communicator,
    const std::uintmax_t                                        resume_length)
    : gravity(gravity)
    , grains(grains)
    , materials(materials)
    , communicator(communicator)
    , file(filename, communicator)
  {
    const std::string energy  = (dim == 2 ? "M L^2/T^2 per L" : "M L^2/T^2");
    const std::string impulse = (dim == 2 ? "M L/T per L" : "M L/T");
    file.open(resume_length, [&](std::ofstream &out) {
      out << "step,time [T],dt [T],kinetic_energy [" << energy
          << "],elastic_energy [" << energy << "],total_energy [" << energy
          << "]";
      // The total is kinetic + elastic + gravity_potential (further right).

      for (unsigned int d = 0; d < dim; ++d)
        out << ",momentum_"
            << "xyz"[d] << " [" << impulse << "]";
      out
        << ",contact_nodes [1],removed_particles [1],newton_iterations [1],"
           "linear_iterations [1],residual_evaluations [1],"
           "residual_rms [1],rejected_steps [1],theta [1],grid_energy_change ["
        << energy << "],transfer_energy_change [" << energy
        << "],gravity_potential [" << energy << "],plastic_work [" << energy
        << "],friction_work [" << energy << "],boundary_work [" << energy
        << "],transfer_work [" << energy << "],leapfrog_work [" << energy
        << "],hypoelastic_correction [" << energy << "],balance_residual ["
        << energy << "]\n"
        << std::flush;
    });
  }



  template <int dim>
  void
  EnergyHistory<dim>::check_written() const
  {
    file.check_written();
  }



  template <int dim>
  std::uintmax_t
  EnergyHistory<dim>::length()
  {
    return file.length();
  }



  template <int dim>
  EnergySummary<dim>
  EnergyHistory<dim>::compute(
    const Particles::ParticleHandler<dim> &particle_handler)
  {
    using Layout = MaterialPointLayout<dim>;
    EnergySummary<dim> summary;
    Tensor<1, dim>     moment;
    for (const auto &particle : particle_handler)
      {
        const auto         properties = particle.get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        if (grains[grain].rigid)
          continue;
        const double         mass     = properties[Layout::mass];
        const Tensor<1, dim> velocity = Layout::get_velocity(properties);
        summary.kinetic += 0.5 * mass * velocity.norm_square();
        summary.momentum += mass * velocity;
        moment += mass * particle.get_location();
        summary.elastic += materials[grains[grain].material]->strain_energy(
          Layout::get_stress(properties),
          properties[Layout::volume],
          properties[Layout::initial_volume]);
      }
    summary.kinetic  = Utilities::MPI::sum(summary.kinetic, communicator);
    summary.elastic  = Utilities::MPI::sum(summary.elastic, communicator);
    summary.momentum = Utilities::MPI::sum(summary.momentum, communicator);
    moment           = Utilities::MPI::sum(moment, communicator);
    if (!have_initial_moment)
      {
        initial_moment      = moment;
        have_initial_moment = true;
      }
    summary.gravity = -gravity * (moment - initial_moment);
    return summary;
  }



  template <int dim>
  EnergySummary<dim>
  EnergyHistory<dim>::summarize(const StepStatistics &statistics)
  {
    Assert(statistics.sums.has_particle_sums && have_initial_moment,
           ExcInternalError());
    EnergySummary<dim> summary;
    summary.kinetic = statistics.sums.kinetic_energy;
    summary.elastic = statistics.sums.elastic_energy;
    Tensor<1, dim> moment;
    for (unsigned int d = 0; d < dim; ++d)
      {
        summary.momentum[d] = statistics.sums.momentum[d];
        moment[d]           = statistics.sums.first_moment[d];
      }
    summary.gravity = -gravity * (moment - initial_moment);
    return summary;
  }



  template <int dim>
  void
  EnergyHistory<dim>::write_row(const unsigned int        step,
                                const double              time,
                                const double              dt,
                                const EnergySummary<dim> &summary,
                                const StepStatistics     &statistics,
                                const EnergyLedger       &ledger,
                                const EnergySummary<dim> &initial)
  {
    if (!file.is_open())
      return;
    std::ofstream &out = file.stream();
    out << step << ',' << std::setprecision(10) << time << ',' << dt << ','
        << std::setprecision(12) << summary.kinetic << ',' << summary.elastic
        << ',' << summary.total();
    for (unsigned int d = 0; d < dim; ++d)
      out << ',' << summary.momentum[d];
    out << ',' << statistics.events.n_contact_nodes << ','
        << statistics.events.n_removed << ','
        << statistics.solver.newton_iterations << ','
        << statistics.solver.linear_iterations << ','
        << statistics.solver.residual_evaluations << ',' << std::setprecision(4)
        << statistics.solver.residual_norm << ',' << statistics.solver.rejected
        << ',' << statistics.solver.theta << ',' << std::setprecision(12)
        << statistics.ledger.grid_energy_change << ','
        << statistics.ledger.transfer_energy_change << ',' << summary.gravity
        << ',' << ledger.plastic_work << ',' << ledger.friction_work << ','
        << ledger.boundary_work << ',' << ledger.transfer << ','
        << ledger.leapfrog << ',' << ledger.hypoelastic_correction << ','
        << ledger.balance(summary, initial) << '\n'
        << std::flush;
  }



  template struct EnergySummary<2>;
  template struct EnergySummary<3>;
  template class EnergyHistory<2>;
  template class EnergyHistory<3>;
} // namespace grainmpm
