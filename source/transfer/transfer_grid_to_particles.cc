// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The grid-to-particle half of Transfer (declared in transfer.h): the
// velocity and position update of the material points, their checks, and
// the end of the step.

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

namespace grainmpm
{
  template <int dim>
  void
  Transfer<dim>::finish_step(Particles::ParticleHandler<dim> &particle_handler,
                             StepStatistics                  &statistics)
  {
    // Positions are final: drop particles that left through open faces,
    // and sort only if some particle (on any rank) changed cells; sorting
    // also sends particles that left this rank's cells to their new owner.
    // Removing is collective (the handler recounts its particles): every
    // rank removes, also with nothing to remove, once any rank has some.
    statistics.events.n_removed = particles_to_remove.size();
    statistics.reduce(grid.get_triangulation().get_communicator());
    if (statistics.events.n_removed > 0)
      {
        particle_handler.remove_particles(particles_to_remove);
        particles_to_remove.clear();
        statistics.events.sorted = true;
      }
    if (statistics.events.sorted)
      particle_handler.sort_particles_into_subdomains_and_cells();
  }



  template <int dim>
  void
  Transfer<dim>::update_deformable(const std::size_t        p,
                                   const ArrayView<double> &properties,
                                   const Point<dim>        &old_position,
                                   const double            *new_values,
                                   const double            *reference_values,
                                   const double            *position_values,
                                   const double             dt,
                                   Point<dim>              &new_position,
                                   Tensor<1, dim>          &new_velocity,
                                   double                  &kinetic_change,
                                   double &increment_energy) const
  {
    using Layout = MaterialPointLayout<dim>;
    // FLIP: v_p += sum_i S_ip (v_i^new - v_i^n); PIC: v_p = sum S v^new;
    // x_p += dt sum_i S_ip v_i (v^L explicit, v^theta implicit).
    Tensor<1, dim> increment, interpolated, moved;
    // (The explicit step moves with v^new: then the same sum is not made
    // twice.)
    const auto sum_entries = [&](auto separate_positions) {
      cache.for_each_entry(p, [&](const unsigned int e) {
        const unsigned int slot  = cache.slots[e];
        const double       shape = cache.shape_values[e];
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double v_new = new_values[slot * dim + d];
            interpolated[d] += shape * v_new;
            if constexpr (decltype(separate_positions)::value)
              moved[d] += shape * position_values[slot * dim + d];
            increment[d] += shape * (v_new - reference_values[slot * dim + d]);
          }
      });
    };
    if (position_values == new_values)
      {
        sum_entries(std::false_type());
        moved = interpolated;
      }
    else
      sum_entries(std::true_type());
    const double         flip         = parameters.time_stepping.flip_fraction;
    const Tensor<1, dim> old_velocity = Layout::get_velocity(properties);
    new_velocity =
      flip * (old_velocity + increment) + (1. - flip) * interpolated;
    new_position = old_position + dt * moved;
    kinetic_change += 0.5 * properties[Layout::mass] *
                      (new_velocity.norm_square() - old_velocity.norm_square());
    increment_energy +=
      0.5 * properties[Layout::mass] * increment.norm_square();
  }



  template <int dim>
  void
  Transfer<dim>::book_energy_changes(const VectorType &masses,
                                     const VectorType &new_velocities,
                                     const VectorType &reference_velocities,
                                     const MassMatrix<dim> *mass_matrix,
                                     const double           kinetic_change,
                                     const double           increment_energy,
                                     LedgerIncrements      &ledger) const
  {
    double grid_kinetic_change = 0., grid_increment_energy = 0.;
    if (mass_matrix != nullptr && !mass_matrix->is_lumped())
      grid_kinetic_change =
        mass_matrix->local_kinetic_energy(new_velocities) -
        mass_matrix->local_kinetic_energy(reference_velocities);
    else
      for (unsigned int s = 0; s < layout.n_slots(); ++s)
        if (!field_is_rigid[layout.field(s)])
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int k      = s * dim + d;
              const double       v_new  = new_velocities.local_element(k);
              const double       v_old  = reference_velocities.local_element(k);
              const double       m_half = 0.5 * masses.local_element(s);
              grid_kinetic_change += m_half * (v_new * v_new - v_old * v_old);
              grid_increment_energy +=
                m_half * (v_new - v_old) * (v_new - v_old);
            }
    ledger.transfer_energy_change = kinetic_change - grid_kinetic_change;
    // The explicit leapfrog's kinetic-strain exchange misses the kinetic
    // energy of the grid-scale part of the step's velocity change (see
    // LedgerIncrements::leapfrog_energy_change).
    if (options.book_leapfrog_energy_change)
      ledger.leapfrog_energy_change = increment_energy - grid_increment_energy;
  }



  template <int dim>
  void
  Transfer<dim>::add_particle_sums(const ArrayView<const double> &properties,
                                   const unsigned int             grain,
                                   const Tensor<1, dim>          &velocity,
                                   const Point<dim>              &position,
                                   ParticleSums                  &sums) const
  {
    using Layout      = MaterialPointLayout<dim>;
    const double mass = properties[Layout::mass];
    sums.kinetic_energy += 0.5 * mass * velocity.norm_square();
    sums.elastic_energy += materials[grains[grain].material]->strain_energy(
      Layout::get_stress(properties),
      properties[Layout::volume],
      properties[Layout::initial_volume]);
    for (unsigned int d = 0; d < dim; ++d)
      {
        sums.momentum[d] += mass * velocity[d];
        sums.first_moment[d] += mass * position[d];
      }
  }



  template <int dim>
  void
  Transfer<dim>::move_particle(
    typename Particles::ParticleHandler<dim>::particle_iterator &particle,
    const Point<dim>                                            &old_position,
    const Point<dim>                                            &new_position,
    StepStatistics &statistics) const
  {
    // Stay in the cell if possible: then no sort is needed.
    const Tensor<1, dim> &h         = grid.cell_size();
    Point<dim>            reference = particle->get_reference_location();
    bool                  inside    = true;
    for (unsigned int d = 0; d < dim; ++d)
      {
        reference[d] += (new_position[d] - old_position[d]) / h[d];
        inside = inside && reference[d] >= 0. && reference[d] <= 1.;
      }
    particle->set_location(new_position);
    if (inside)
      particle->set_reference_location(reference);
    else
      statistics.events.sorted = true;
  }



  template <int dim>
  void
  Transfer<dim>::grid_to_particles(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &masses,
    const VectorType                &velocities_new,
    const VectorType                &velocities_p2g,
    const VectorType                &position_velocities,
    const double                     time,
    const double                     dt,
    StepStatistics                  &statistics,
    const MassMatrix<dim>           *mass_matrix)
  {
    using Layout                           = MaterialPointLayout<dim>;
    double       max_speed_square          = 0.;
    double       particle_kinetic_change   = 0.;
    double       particle_increment_energy = 0.; // sum 1/2 m_p |dv_p|^2
    std::string  error;
    bool         error_from_rigid = false;
    ParticleSums sums;
    sums.has_particle_sums = true;
    velocities_new.update_ghost_values();
    velocities_p2g.update_ghost_values();
    position_velocities.update_ghost_values();

    for_each_particle(
      particle_handler,
      [&](const std::size_t p, auto &particle) __attribute__((always_inline)) {
        // After an error, go on only to find a prescribed velocity that
        // is not finite: it is the cause of the others.
        if (error_from_rigid)
          return;
        auto               properties   = particle->get_properties();
        const unsigned int grain        = Layout::get_grain(properties);
        const bool         rigid        = grains[grain].rigid;
        const Point<dim>   old_position = particle->get_location();
        Point<dim>         new_position;
        Tensor<1, dim>     new_velocity;
        // Rigid grains follow their prescribed velocity (midpoint rule); a
        // deformable point is checked (ParticleUpdateCheck::check()). (The
        // messages are initialised, not assigned: an empty string per point
        // costs nothing then.)
        if (!rigid)
          update_deformable(p,
                            properties,
                            old_position,
                            velocities_new.begin(),
                            velocities_p2g.begin(),
                            position_velocities.begin(),
                            dt,
                            new_position,
                            new_velocity,
                            particle_kinetic_change,
                            particle_increment_energy);
        std::string failure = rigid ?
                                rigid_motion.move_point(grain,
                                                        particle->get_id(),
                                                        old_position,
                                                        time,
                                                        dt,
                                                        new_position,
                                                        new_velocity) :
                                update_check.check(particle->get_id(),
                                                   grain,
                                                   old_position,
                                                   new_position,
                                                   new_velocity,
                                                   time,
                                                   dt);
        if (!failure.empty())
          {
            // A prescribed velocity that is not finite is the cause of any
            // other error: its message wins.
            if (error.empty() || rigid)
              error = std::move(failure);
            error_from_rigid = rigid;
            return;
          }
        Layout::set_velocity(new_velocity, properties);
        max_speed_square =
          std::max(max_speed_square, new_velocity.norm_square());

        bool              removed = false;
        const std::string box_failure =
          update_check.leave_box(particle->get_id(),
                                 grain,
                                 rigid,
                                 new_position,
                                 time + dt,
                                 statistics.events.n_held_at_walls,
                                 removed);
        if (!box_failure.empty() || removed)
          {
            if (removed)
              particles_to_remove.push_back(particle);
            else if (error.empty())
              error = box_failure;
            return;
          }

        if (options.gather_particle_sums && !rigid)
          add_particle_sums(
            properties, grain, new_velocity, new_position, sums);
        move_particle(particle, old_position, new_position, statistics);
      });
    throw_on_all_ranks(error, grid.get_triangulation().get_communicator());
    statistics.events.max_speed = std::sqrt(max_speed_square);
    if (options.gather_particle_sums)
      statistics.sums = sums;

    book_energy_changes(masses,
                        velocities_new,
                        velocities_p2g,
                        mass_matrix,
                        particle_kinetic_change,
                        particle_increment_energy,
                        statistics.ledger);
  }



#define GRAINMPM_INSTANTIATE(dim)                                             \
  template void Transfer<dim>::grid_to_particles(                             \
    Particles::ParticleHandler<dim> &,                                        \
    const VectorType &,                                                       \
    const VectorType &,                                                       \
    const VectorType &,                                                       \
    const VectorType &,                                                       \
    const double,                                                             \
    const double,                                                             \
    StepStatistics &,                                                         \
    const MassMatrix<dim> *);                                                 \
  template void Transfer<dim>::finish_step(Particles::ParticleHandler<dim> &, \
                                           StepStatistics &);

  GRAINMPM_INSTANTIATE(2)
  GRAINMPM_INSTANTIATE(3)
#undef GRAINMPM_INSTANTIATE
} // namespace grainmpm
