// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/history_file.h>
#include <grainmpm/postprocess/postprocessor.h>

namespace grainmpm
{
  template <int dim>
  Postprocessor<dim>::Postprocessor(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
    const Particles::ParticleHandler<dim> &particle_handler,
    const HistoryLengths                  &lengths,
    const MPI_Comm                         communicator)
    : parameters(parameters)
    , n_grains(grains.size())
  {
    const std::string &directory = parameters.output.directory;
    // Photoelastic fringe order per unit principal stress difference,
    // per grain: thickness / material fringe value.
    std::vector<double> fringe_factors;
    for (const auto &grain : grains)
      {
        const MaterialParameters &material =
          parameters.materials[grain.material];
        fringe_factors.push_back(material.material_fringe_value > 0. ?
                                   material.thickness /
                                     material.material_fringe_value :
                                   0.);
        grain_is_rigid.push_back(grain.rigid);
      }
    output_writer = std::make_unique<OutputWriter<dim>>(parameters.output,
                                                        grid,
                                                        fringe_factors);
    energy_history =
      std::make_unique<EnergyHistory<dim>>(directory + "/energy.csv",
                                           grains,
                                           materials,
                                           parameters.physics.gravity,
                                           communicator,
                                           lengths.energy);
    grain_history = std::make_unique<GrainHistory<dim>>(
      directory + "/grains.csv", grain_is_rigid, communicator, lengths.grains);
    std::vector<Point<dim>> centres;
    for (const auto &motion : grain_history->compute(particle_handler))
      centres.push_back(motion.centre_of_mass);
    reaction_history =
      std::make_unique<ReactionHistory<dim>>(directory + "/walls.csv",
                                             grid,
                                             grains,
                                             centres,
                                             particle_handler,
                                             communicator,
                                             lengths.walls);
    if (parameters.output.write_contacts)
      contact_history = std::make_unique<ContactHistory<dim>>(
        directory + "/contacts.csv",
        parameters.contact.model == ContactModel::coulomb_friction ?
          parameters.contact.friction_coefficient :
          0.,
        communicator,
        lengths.contacts);
  }



  template <int dim>
  void
  Postprocessor<dim>::copy_histories(const std::string    &source,
                                     const std::string    &directory,
                                     const HistoryLengths &lengths,
                                     const MPI_Comm        communicator)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          for (const auto &[name, length] :
               {std::make_pair("energy.csv", lengths.energy),
                std::make_pair("grains.csv", lengths.grains),
                std::make_pair("walls.csv", lengths.walls),
                std::make_pair("contacts.csv", lengths.contacts)})
            copy_history_file(source + "/" + name,
                              directory + "/" + name,
                              length);
        }
      catch (const InputError &exception)
        {
          error = exception.what();
        }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  typename Postprocessor<dim>::HistoryLengths
  Postprocessor<dim>::get_lengths() const
  {
    HistoryLengths lengths;
    lengths.energy   = energy_history->length();
    lengths.grains   = grain_history->length();
    lengths.walls    = reaction_history->length();
    lengths.contacts = contact_history ? contact_history->length() : 0;
    return lengths;
  }



  template <int dim>
  double
  Postprocessor<dim>::largest_grain_speed(
    const Particles::ParticleHandler<dim> &particle_handler) const
  {
    double speed = 0.;
    for (const GrainMotion<dim> &motion :
         grain_history->compute(particle_handler))
      speed = std::max(speed,
                       motion.velocity.norm() +
                         motion.angular_velocity.norm() * motion.max_distance);
    return speed;
  }



  template <int dim>
  EnergySummary<dim>
  Postprocessor<dim>::compute_energies(
    const Particles::ParticleHandler<dim> &particle_handler,
    const StepStatistics                  &statistics)
  {
    return statistics.sums.has_particle_sums ?
             energy_history->summarize(statistics) :
             energy_history->compute(particle_handler);
  }



  template <int dim>
  void
  Postprocessor<dim>::write_initial_row(const EnergySummary<dim> &initial,
                                        const EnergyLedger       &ledger)
  {
    energy_history->write_row(
      0, 0., 0., initial, StepStatistics(), ledger, initial);
  }



  template <int dim>
  void
  Postprocessor<dim>::write_step(
    const unsigned int                     step,
    const double                           time,
    const double                           dt,
    const StepStatistics                  &statistics,
    const ConstraintImpulses<dim>         &impulses,
    const EnergySummary<dim>              &energies,
    const EnergyLedger                    &ledger,
    const EnergySummary<dim>              &initial_energies,
    const Particles::ParticleHandler<dim> &particle_handler)
  {
    reaction_history->write_row(step, time, dt, impulses, particle_handler);
    if (contact_history)
      contact_history->add_step(impulses);
    energy_history->write_row(
      step, time, dt, energies, statistics, ledger, initial_energies);
  }



  template <int dim>
  void
  Postprocessor<dim>::write_output(
    const unsigned int                     step,
    const double                           time,
    const unsigned int                     index,
    const Particles::ParticleHandler<dim> &particle_handler,
    const TimeIntegrator<dim>             &stepper)
  {
    // The histories written every step (energy, walls) on rank 0: a failed
    // write stops every rank here, with the file cut back to its last whole
    // row, before an output file of this step can stop the run first.
    energy_history->check_written();
    reaction_history->check_written();
    if (parameters.output.write_particles)
      output_writer->write_particles(particle_handler, time, index);
    if (parameters.output.write_grid && step > 0)
      output_writer->write_grid(stepper, time, index);
    const std::vector<GrainMotion<dim>> motions =
      grain_history->compute(particle_handler);
    std::vector<GrainContactForce<dim>> contact_forces;
    if (contact_history)
      {
        contact_forces = contact_history->collect(time);
        contact_history->write(contact_forces, time);
        output_writer->write_contacts(
          contact_forces, motions, grain_is_rigid, time, index);
      }
    grain_history->write(
      motions,
      ContactHistory<dim>::coordination_numbers(contact_forces, n_grains),
      time,
      parameters.output.write_grain_history);
    // The grain history, written at outputs, likewise.
    grain_history->check_written();
  }



  template <int dim>
  void
  Postprocessor<dim>::prepare_checkpoint()
  {
    if (contact_history)
      contact_history->gather_sums();
  }



  template class Postprocessor<2>;
  template class Postprocessor<3>;
} // namespace grainmpm
