// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/time_integration/explicit_leapfrog.h>

namespace grainmpm
{
  namespace
  {
    /**
     * What the explicit step asks of the transfer: a point that moves more
     * than a cell in one step is a blow-up; the update-stress-first step
     * gathers the particle sums in its last pass; USL books the leapfrog's
     * energy change.
     */
    TransferOptions
    explicit_transfer_options(const TimeSteppingParameters &time_stepping)
    {
      TransferOptions options;
      options.limit_move_to_one_cell = true;
      options.divergence_advice =
        "Use a smaller time step; if that does not help, check the "
        "materials and velocities.";
      options.gather_particle_sums =
        time_stepping.stress_update == StressUpdate::usf;
      options.book_leapfrog_energy_change =
        time_stepping.stress_update == StressUpdate::usl;
      return options;
    }
  } // namespace



  template <int dim>
  ExplicitLeapfrog<dim>::ExplicitLeapfrog(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    : parameters(parameters)
    , transfer(parameters,
               grid,
               grains,
               materials,
               explicit_transfer_options(parameters.time_stepping))
    , contact(parameters.contact,
              grid,
              transfer.get_rigid_motion(),
              transfer.get_field_is_rigid(),
              transfer.get_field_keeps_shape(),
              grains,
              parameters.grains)
  {}



  template <int dim>
  StepStatistics
  ExplicitLeapfrog<dim>::advance(
    Particles::ParticleHandler<dim> &particle_handler,
    const double                     time,
    const double                     dt)
  {
    StepStatistics statistics;

    // Everything that depends only on the positions at t^n, once per step.
    begin_step(transfer, contact, particle_handler, time, dt, state);
    const GrainFieldLayout<dim> &layout = transfer.get_layout();

    copy_slot_vector(state.velocities_p2g, velocities_old);
    if (parameters.time_stepping.stress_update == StressUpdate::usf)
      {
        // Eqs. (8)-(10): strain from the (contact-corrected) v^n, then the
        // forces of eq. (7) from sigma^{n+1/2}, V^{n+1/2}.
        statistics.events.n_contact_nodes +=
          apply_constraints(velocities_old, true);
        transfer.update_particle_states_and_forces(particle_handler,
                                                   velocities_old,
                                                   dt,
                                                   parameters.physics.gravity,
                                                   forces,
                                                   statistics.ledger);
      }
    else
      transfer.compute_forces(particle_handler,
                              parameters.physics.gravity,
                              forces);

    integrate_grid_velocities(dt);
    copy_slot_vector(state.velocities_new, unconstrained_velocities);
    statistics.events.n_contact_nodes +=
      apply_constraints(state.velocities_new, true);
    const auto [friction_work, boundary_work] =
      contact.constraint_work(layout,
                              state.masses,
                              unconstrained_velocities,
                              state.velocities_new,
                              state.velocities_new);
    statistics.ledger.friction_work += friction_work;
    statistics.ledger.boundary_work += boundary_work;
    transfer.grid_to_particles(particle_handler,
                               state.masses,
                               state.velocities_new,
                               state.velocities_p2g,
                               state.velocities_new,
                               time,
                               dt,
                               statistics);
    // (After the particles, which read no rigid slot: a prescribed velocity
    // that is not finite at t + dt is reported at a material point.)
    contact.prescribe_rigid_velocities(layout, state.velocities_new, time + dt);

    if (parameters.time_stepping.stress_update == StressUpdate::usl)
      // The strain velocity is v^{n+1}, the constrained velocity that moved
      // the particles.
      transfer.update_particle_states(particle_handler,
                                      state.velocities_new,
                                      dt,
                                      statistics.ledger);
    else if (parameters.time_stepping.stress_update == StressUpdate::musl)
      {
        // The strain velocity remapped from the new particle momenta.
        transfer.particles_to_grid(particle_handler,
                                   nullptr,
                                   state.momenta,
                                   nullptr);
        transfer.velocities_from_momenta(state.masses,
                                         state.momenta,
                                         velocities_old);
        contact.prescribe_rigid_velocities(layout, velocities_old, time + dt);
        // (The strain velocity only: no momentum changes hands here.)
        statistics.events.n_contact_nodes +=
          apply_constraints(velocities_old, false);
        transfer.update_particle_states(particle_handler,
                                        velocities_old,
                                        dt,
                                        statistics.ledger);
      }

    transfer.finish_step(particle_handler, statistics);
    return statistics;
  }



  template <int dim>
  unsigned int
  ExplicitLeapfrog<dim>::apply_constraints(VectorType &velocities,
                                           const bool  record)
  {
    const GrainFieldLayout<dim> &layout    = transfer.get_layout();
    ConstraintImpulses<dim>     *impulses  = record ? &state.impulses : nullptr;
    const unsigned int           n_contact = contact.apply_contact(layout,
                                                         state.masses,
                                                         state.normals,
                                                         velocities,
                                                         &state.node_in_contact,
                                                         impulses);
    contact.apply_walls(layout, velocities, &state.masses, impulses);
    return n_contact;
  }



  template <int dim>
  void
  ExplicitLeapfrog<dim>::integrate_grid_velocities(const double dt)
  {
    const GrainFieldLayout<dim> &layout         = transfer.get_layout();
    const std::vector<bool>     &field_is_rigid = transfer.get_field_is_rigid();
    copy_slot_vector(velocities_old, state.velocities_new);
    // A slot whose mass is round-off (a point on the edge of the node's
    // support, weight ~1e-32) keeps its velocity: f / m would be ~1e12
    // there, and with USL that velocity strains the points beside it (a
    // block started in its lithostatic equilibrium then moves).
    const double round_off_mass = 1e-12 * state.masses.linfty_norm();
    for (unsigned int slot = 0; slot < layout.n_slots(); ++slot)
      {
        const double mass = state.masses.local_element(slot);
        if (mass > round_off_mass && !field_is_rigid[layout.field(slot)])
          for (unsigned int d = 0; d < dim; ++d)
            state.velocities_new.local_element(slot * dim + d) +=
              dt * forces.local_element(slot * dim + d) / mass;
      }
  }



  template class ExplicitLeapfrog<2>;
  template class ExplicitLeapfrog<3>;
} // namespace grainmpm
