// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/time_integration/implicit_theta.h>
#include <grainmpm/time_integration/time_step_controller.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace grainmpm
{
  namespace
  {
    /** Velocity scale U of the Newton solver. */
    template <int dim>
    double
    velocity_scale(
      const Parameters<dim>                                      &parameters,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    {
      if (parameters.nonlinear_solver.velocity_scale > 0.)
        return parameters.nonlinear_solver.velocity_scale;
      const double wave_speed = largest_wave_speed(grains, materials);
      return wave_speed > 0. ? wave_speed : 1.;
    }

    /** What the implicit step asks of the transfer: only the advice. */
    TransferOptions
    implicit_transfer_options()
    {
      TransferOptions options;
      options.divergence_advice =
        "Use a smaller time step, or tighten Nonlinear solver/Tolerance.";
      return options;
    }
  } // namespace



  template <int dim>
  ImplicitTheta<dim>::ImplicitTheta(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
    const bool                                                  quiet)
    : parameters(parameters)
    , transfer(parameters, grid, grains, materials, implicit_transfer_options())
    , contact(parameters.contact,
              grid,
              transfer.get_rigid_motion(),
              transfer.get_field_is_rigid(),
              transfer.get_field_keeps_shape(),
              grains,
              parameters.grains)
    , nominal_step_at_rest(
        nominal_time_step(parameters.time_stepping,
                          grid.minimum_cell_size(),
                          largest_wave_speed(grains, materials),
                          0.))
    , steps_grow(parameters.time_stepping.largest_time_step(
                   grid.minimum_cell_size(),
                   largest_wave_speed(grains, materials)) >
                 nominal_step_at_rest)
    , unit_cfl_step(grid.minimum_cell_size() /
                    std::max(largest_wave_speed(grains, materials),
                             std::numeric_limits<double>::min()))
    , residual(contact, grid, materials)
    , step_error(grains)
    , solver(parameters.nonlinear_solver,
             parameters.linear_solver,
             velocity_scale(parameters, grains, materials),
             ConditionalOStream(
               std::cout,
               parameters.nonlinear_solver.verbose && !quiet &&
                 Utilities::MPI::this_mpi_process(
                   grid.get_triangulation().get_communicator()) == 0))
  {
    residual.set_status_band(parameters.nonlinear_solver.status_tolerance *
                             solver.get_velocity_scale());
    // The factorisation on one process only.
    const Preconditioner preconditioner =
      parameters.linear_solver.preconditioner;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(
      grid.get_triangulation().get_communicator());
    if (preconditioner == Preconditioner::sparse_cholesky && n_ranks > 1)
      throw InputError("Linear solver/Preconditioner = sparse Cholesky",
                       "this preconditioner factorises the whole matrix on "
                       "one MPI process, and this run has " +
                         std::to_string(n_ranks) +
                         " processes; use AMG or automatic in parallel.");
    if (preconditioner == Preconditioner::sparse_cholesky ||
        (preconditioner == Preconditioner::automatic && n_ranks == 1))
      residual.set_preconditioner_inverse(
        ElasticPreconditioner<dim>::Inverse::cholesky);
  }



  template <int dim>
  ThetaResidual<dim> &
  ImplicitTheta<dim>::prepare(Particles::ParticleHandler<dim> &particle_handler,
                              const double                     time,
                              const double                     dt,
                              const bool                       freeze)
  {
    // Frozen at t^n: shape functions, slots, masses, normals; v^n with
    // contact and walls.
    begin_step(transfer, contact, particle_handler, time, dt, state);
    const GrainFieldLayout<dim> &layout = transfer.get_layout();
    mass_matrix.reinit(transfer,
                       particle_handler,
                       state.masses,
                       parameters.time_stepping.consistent_mass_fraction);
    if (!mass_matrix.is_lumped())
      {
        // v^n = M^{-1} p in place of p / m.
        mass_matrix.solve(state.momenta, state.velocities_p2g);
        contact.prescribe_rigid_velocities(layout, state.velocities_p2g, time);
      }
    copy_slot_vector(state.velocities_p2g, velocities_old);
    contact.apply_contact(layout,
                          state.masses,
                          state.normals,
                          velocities_old,
                          &state.node_in_contact,
                          &state.impulses);
    contact.apply_walls(layout, velocities_old, &state.masses, &state.impulses);
    copy_slot_vector(velocities_old, rigid_velocities);
    contact.prescribe_rigid_velocities(layout, rigid_velocities, time + dt);

    residual.reinit(transfer,
                    particle_handler,
                    mass_matrix,
                    state.masses,
                    state.normals,
                    velocities_old,
                    rigid_velocities,
                    parameters.physics.gravity,
                    step_theta(),
                    dt);

    // The first iterate: v^n, rigid slots at their velocity at t + dt.
    copy_slot_vector(velocities_old, unknowns);
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      if (transfer.get_field_is_rigid()[layout.field(s)])
        for (unsigned int d = 0; d < dim; ++d)
          unknowns.local_element(s * dim + d) =
            rigid_velocities.local_element(s * dim + d);
    if (freeze)
      residual.freeze_status(unknowns);
    return residual;
  }



  template <int dim>
  StepStatistics
  ImplicitTheta<dim>::advance(Particles::ParticleHandler<dim> &particle_handler,
                              const double                     time,
                              const double                     dt)
  {
    StepStatistics      statistics;
    const unsigned long evaluations_at_start =
      residual.n_residual_evaluations();
    // The solver freezes the contact status at its first iterate itself.
    prepare(particle_handler, time, dt, false);
    if (parameters.nonlinear_solver.keep_contact_status)
      residual.start_status_from(held_status);
    final_residual.reinit(unknowns, true);

    const NewtonStatistics newton =
      solver.solve(residual, unknowns, dt / unit_cfl_step);
    statistics.solver.newton_iterations = newton.iterations;
    statistics.solver.linear_iterations = newton.linear_iterations;
    statistics.solver.residual_norm     = newton.residual_norm;
    statistics.solver.status_changes    = newton.status_changes;
    statistics.solver.theta             = step_theta();
    if (!newton.converged)
      {
        statistics.solver.converged = false;
        statistics.solver.failure   = newton.failure;
        statistics.solver.failed_at_first_iterate =
          newton.failed_at_first_iterate;
        statistics.solver.residual_evaluations =
          residual.n_residual_evaluations() - evaluations_at_start;
        return statistics;
      }

    // Momentum-exact end velocity v* = V - R_raw(V) = v^n + dt (f / m + g),
    // projected with the converged status.
    residual.raw_residual_at(unknowns, final_residual);
    unknowns -= final_residual;
    statistics.events.n_contact_nodes = residual.project(unknowns,
                                                         state.velocities_new,
                                                         &state.node_in_contact,
                                                         &state.impulses);
    theta_velocities.reinit(unknowns, true);
    residual.theta_velocities(state.velocities_new, theta_velocities);
    const GrainFieldLayout<dim> &layout       = transfer.get_layout();
    const auto [friction_work, boundary_work] = contact.constraint_work(
      layout, state.masses, unknowns, state.velocities_new, theta_velocities);
    statistics.ledger.friction_work += friction_work;
    statistics.ledger.boundary_work += boundary_work;

    // Grid energies before and after (deformable slots).
    const double kinetic_old =
      mass_matrix.local_kinetic_energy(state.velocities_p2g);
    const double kinetic_new =
      mass_matrix.local_kinetic_energy(state.velocities_new);
    if (const std::string failure = energy_error(particle_handler,
                                                 kinetic_old,
                                                 kinetic_new,
                                                 friction_work - boundary_work,
                                                 dt);
        !failure.empty())
      {
        statistics.solver.converged             = false;
        statistics.solver.rejected_for_accuracy = true;
        statistics.solver.failure               = failure;
        statistics.solver.residual_evaluations =
          residual.n_residual_evaluations() - evaluations_at_start;
        return statistics;
      }
    double energies[4] = {kinetic_old, kinetic_new, 0., 0.};
    energies[2]        = residual.old_strain_energy();
    transfer.update_particle_states(
      particle_handler, theta_velocities, dt, statistics.ledger, &energies[3]);
    Utilities::MPI::sum(ArrayView<const double>(energies, 4),
                        layout.get_communicator(),
                        ArrayView<double>(energies, 4));
    grid_energies = {energies[0] + energies[2], energies[1] + energies[3]};
    // Quasi-static: the grid kinetic energy is a small part of the elastic
    // energy at both ends of the step.
    constexpr double quasi_static_kinetic_fraction = 0.01;
    last_step_quasi_static =
      energies[3] > 0. &&
      energies[0] <= quasi_static_kinetic_fraction * energies[2] &&
      energies[1] <= quasi_static_kinetic_fraction * energies[3];
    statistics.ledger.grid_energy_change =
      grid_energies.second - grid_energies.first;

    // The error estimate only where it sizes the steps (grown steps).
    const bool estimate_error =
      steps_grow && parameters.time_stepping.step_error_tolerance > 0.;
    if (estimate_error)
      step_error.record_velocities(particle_handler);
    transfer.grid_to_particles(particle_handler,
                               state.masses,
                               state.velocities_new,
                               state.velocities_p2g,
                               theta_velocities,
                               time,
                               dt,
                               statistics,
                               &mass_matrix);
    if (estimate_error)
      statistics.solver.step_error =
        step_error.estimate(particle_handler, dt, layout.get_communicator());
    if (parameters.nonlinear_solver.keep_contact_status)
      held_status.record(residual.get_contact_status(),
                         transfer.get_layout(),
                         contact.get_grid());
    transfer.finish_step(particle_handler, statistics);
    statistics.solver.residual_evaluations =
      residual.n_residual_evaluations() - evaluations_at_start;
    return statistics;
  }



  template <int dim>
  double
  ImplicitTheta<dim>::step_theta() const
  {
    const TimeSteppingParameters &stepping = parameters.time_stepping;
    if (steps_grow && last_step_quasi_static)
      return std::max(stepping.theta, stepping.quasi_static_theta);
    return stepping.theta;
  }



  template <int dim>
  std::string
  ImplicitTheta<dim>::energy_error(
    Particles::ParticleHandler<dim> &particle_handler,
    const double                     kinetic_old,
    const double                     kinetic_new,
    const double                     constraint_work,
    const double                     dt) const
  {
    const TimeSteppingParameters &stepping = parameters.time_stepping;
    // (A step cut and grown back to the nominal one may exceed it by a
    // round-off.)
    if (!(steps_grow && stepping.energy_error > 0. &&
          dt > (1. + 1e-9) * nominal_step_at_rest))
      return "";
    // The grid step's share of the energy balance, as the ledger books it
    // after the step (theory section 14), from a trial constitutive update,
    // less the work of gravity on the deformable slots over the step.
    const GrainFieldLayout<dim> &layout         = transfer.get_layout();
    const std::vector<bool>     &field_is_rigid = transfer.get_field_is_rigid();
    const Tensor<1, dim>        &gravity        = parameters.physics.gravity;
    double                       gravity_work   = 0.;
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      if (!field_is_rigid[layout.field(s)])
        for (unsigned int d = 0; d < dim; ++d)
          gravity_work += dt * state.masses.local_element(s) * gravity[d] *
                          theta_velocities.local_element(s * dim + d);
    double energies[7] = {kinetic_old,
                          kinetic_new,
                          residual.old_strain_energy(),
                          0.,
                          constraint_work,
                          contact.normal_dissipation(transfer.get_layout(),
                                                     state.masses,
                                                     state.normals,
                                                     unknowns,
                                                     state.velocities_new,
                                                     theta_velocities),
                          gravity_work};
    energies[3]        = transfer.trial_strain_energy(particle_handler,
                                               theta_velocities,
                                               dt,
                                               energies[4]);
    Utilities::MPI::sum(ArrayView<const double>(energies, 7),
                        layout.get_communicator(),
                        ArrayView<double>(energies, 7));
    const double before  = energies[0] + energies[2];
    const double after   = energies[1] + energies[3];
    const double created = after - before + energies[4] - energies[6];
    const double energy  = std::max(before, after);
    // A step that stops an approach at once (an impact the step does not
    // resolve) loses the energy of the approach to the normal reactions.
    if (energies[5] > stepping.energy_error * energy)
      {
        std::ostringstream message;
        message << "the normal contact reactions took " << energies[5] / energy
                << " of the grid energy (an impact the step does not "
                   "resolve), more than Time stepping/Energy error per "
                   "step = "
                << stepping.energy_error;
        return message.str();
      }
    if (!(created > stepping.energy_error * energy))
      return "";
    std::ostringstream message;
    message << "the step created " << created / energy
            << " of the grid energy, more than Time stepping/Energy error "
               "per step = "
            << stepping.energy_error;
    return message.str();
  }



  template class ImplicitTheta<2>;
  template class ImplicitTheta<3>;
} // namespace grainmpm
