// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <type_traits>

namespace grainmpm
{
  namespace
  {
    /**
     * Store the new @p stress and @p plastic_strain of a particle with
     * @p properties, update its deformation gradient by the increment
     * @p increment (dt grad v: F <- (I + dt grad v) F) and its volume
     * det(F) V_0. Returns the new volume.
     */
    template <int dim>
    double
    store_particle_state(const ArrayView<double>     &properties,
                         const SymmetricTensor<2, 3> &stress,
                         const double                 plastic_strain,
                         const Tensor<2, dim>        &increment)
    {
      using Layout = MaterialPointLayout<dim>;
      Layout::set_stress(stress, properties);
      properties[Layout::plastic_strain] = plastic_strain;
      Tensor<2, dim> F = Layout::get_deformation_gradient(properties);
      F += increment * F;
      Layout::set_deformation_gradient(F, properties);
      properties[Layout::volume] =
        determinant(F) * properties[Layout::initial_volume];
      return properties[Layout::volume];
    }



  } // namespace



  template <int dim>
  Transfer<dim>::Transfer(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
    const TransferOptions                                      &options)
    : parameters(parameters)
    , grid(grid)
    , grains(grains)
    , materials(materials)
    , options(options)
    , rigid_motion(grains, parameters.grains, grid)
    , update_check(parameters, grid, this->options)
    , field_of_grain(grains.size())
    , field_is_rigid(grains.size(), false)
  {
    int shared_field = -1;
    for (unsigned int g = 0; g < grains.size(); ++g)
      {
        field_of_grain[g] = g;
        field_is_rigid[g] = grains[g].rigid;
        if (parameters.contact.model == ContactModel::none && !grains[g].rigid)
          {
            if (shared_field < 0)
              shared_field = g;
            field_of_grain[g] = shared_field;
          }
        several_fields =
          several_fields || field_of_grain[g] != field_of_grain[0];
      }
  }



  template <int dim>
  void
  Transfer<dim>::reinit(const Particles::ParticleHandler<dim> &particle_handler)
  {
    // A particle's box is its share of the regular arrangement of the
    // points: half the point spacing on each side.
    Tensor<1, dim> half_width;
    for (unsigned int d = 0; d < dim; ++d)
      half_width[d] = 0.5 * grid.cell_size()[d] /
                      parameters.material_points.particles_per_cell;
    cache.reinit(grid,
                 particle_handler,
                 field_of_grain,
                 parameters.material_points.shape_functions,
                 half_width);
    layout.reinit(cache, grid);
  }



  template <int dim>
  void
  Transfer<dim>::particles_to_grid(
    const Particles::ParticleHandler<dim> &particle_handler,
    VectorType                            *masses,
    VectorType                            &momenta,
    VectorType                            *mass_gradients,
    VectorType                            *volumes) const
  {
    using Layout = MaterialPointLayout<dim>;
    if (masses != nullptr)
      layout.reinit_vector(*masses, 1);
    layout.reinit_vector(momenta, dim);
    if (mass_gradients != nullptr)
      layout.reinit_vector(*mass_gradients, dim);
    if (volumes != nullptr)
      layout.reinit_vector(*volumes, 1);

    // The loop with or without masses, mass gradients and volumes
    // (compile-time choices: a test in the inner loop costs 10 % of the
    // transfer).
    const auto scatter =
      [&](auto with_masses, auto with_gradients, auto with_volumes) {
        constexpr bool add_masses    = decltype(with_masses)::value;
        constexpr bool add_gradients = decltype(with_gradients)::value;
        constexpr bool add_volumes   = decltype(with_volumes)::value;
        double *const  mass_values   = add_masses ? masses->begin() : nullptr;
        double *const  momentum      = momenta.begin();
        double *const  gradient_sum =
          add_gradients ? mass_gradients->begin() : nullptr;
        double *const volume_sum = add_volumes ? volumes->begin() : nullptr;
        for_each_particle(
          particle_handler,
          [&](const std::size_t p, const auto &particle)
            __attribute__((always_inline)) {
              const auto   properties = particle->get_properties();
              const double mass       = properties[Layout::mass];
              const double volume     = properties[Layout::volume];
              cache.for_each_entry(p, [&](const unsigned int e) {
                const unsigned int    slot     = cache.slots[e];
                const double          shape    = cache.shape_values[e];
                const Tensor<1, dim> &gradient = cache.shape_gradients[e];
                if constexpr (add_masses)
                  mass_values[slot] += mass * shape;
                if constexpr (add_volumes)
                  volume_sum[slot] += volume * shape;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    momentum[slot * dim + d] +=
                      mass * shape * properties[Layout::velocity + d];
                    if constexpr (add_gradients)
                      gradient_sum[slot * dim + d] += mass * gradient[d];
                  }
              });
            });
      };
    Assert(mass_gradients == nullptr || masses != nullptr,
           ExcMessage("Mass gradients come with masses."));
    Assert(volumes == nullptr || masses != nullptr,
           ExcMessage("Volumes come with masses."));
    using Yes = std::true_type;
    using No  = std::false_type;
    if (masses == nullptr)
      scatter(No(), No(), No());
    else if (mass_gradients != nullptr)
      {
        if (volumes != nullptr)
          scatter(Yes(), Yes(), Yes());
        else
          scatter(Yes(), Yes(), No());
      }
    else if (volumes != nullptr)
      scatter(Yes(), No(), Yes());
    else
      scatter(Yes(), No(), No());
    // Sums at ghost slots go to their owners.
    if (masses != nullptr)
      masses->compress(VectorOperation::add);
    momenta.compress(VectorOperation::add);
    if (mass_gradients != nullptr)
      mass_gradients->compress(VectorOperation::add);
    if (volumes != nullptr)
      volumes->compress(VectorOperation::add);
  }



  template <int dim>
  void
  Transfer<dim>::velocities_from_momenta(const VectorType &masses,
                                         const VectorType &momenta,
                                         VectorType       &velocities) const
  {
    // Owned slots; ghost slots get their values from the owner when a
    // particle loop needs them.
    layout.reinit_vector(velocities, dim);
    for (unsigned int slot = 0; slot < layout.n_slots(); ++slot)
      {
        const double mass = masses.local_element(slot);
        if (mass > 0.)
          for (unsigned int d = 0; d < dim; ++d)
            velocities.local_element(slot * dim + d) =
              momenta.local_element(slot * dim + d) / mass;
      }
  }



  template <int dim>
  void
  Transfer<dim>::compute_forces(
    const Particles::ParticleHandler<dim> &particle_handler,
    const Tensor<1, dim>                  &gravity,
    VectorType                            &forces) const
  {
    using Layout = MaterialPointLayout<dim>;
    layout.reinit_vector(forces, dim);
    for_each_particle(
      particle_handler,
      [&](const std::size_t p, const auto &particle)
        __attribute__((always_inline)) {
          const auto properties = particle->get_properties();
          if (grains[Layout::get_grain(properties)].rigid)
            return;
          add_force(p,
                    properties[Layout::mass],
                    properties[Layout::volume],
                    Layout::get_stress(properties),
                    gravity,
                    forces.begin());
        });
    forces.compress(VectorOperation::add);
  }



  template <int dim>
  void
  Transfer<dim>::update_particle_states(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    double                          &plastic_work,
    double                          *strain_energy) const
  {
    update_states(particle_handler,
                  velocities,
                  dt,
                  plastic_work,
                  strain_energy,
                  Tensor<1, dim>(),
                  nullptr);
  }



  template <int dim>
  void
  Transfer<dim>::update_particle_states_and_forces(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    const Tensor<1, dim>            &gravity,
    VectorType                      &forces,
    double                          &plastic_work) const
  {
    layout.reinit_vector(forces, dim);
    update_states(particle_handler,
                  velocities,
                  dt,
                  plastic_work,
                  nullptr,
                  gravity,
                  &forces);
    forces.compress(VectorOperation::add);
  }



  template <int dim>
  void
  Transfer<dim>::update_states(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    double                          &plastic_work,
    double                          *strain_energy,
    const Tensor<1, dim>            &gravity,
    VectorType                      *forces) const
  {
    using Layout = MaterialPointLayout<dim>;
    velocities.update_ghost_values();
    const double *const values = velocities.begin();
    double *const force_array  = forces != nullptr ? forces->begin() : nullptr;
    for_each_particle(
      particle_handler,
      [&](const std::size_t p, auto &particle) __attribute__((always_inline)) {
        auto               properties = particle->get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        if (grains[grain].rigid)
          return;
        // dt L_p = dt sum_i v_i (x) grad S_ip, then the constitutive model
        // (Cummins & Brackbill eqs. 8-10).
        Tensor<2, dim> increment = velocity_gradient(p, values);
        increment *= dt;
        const ConstitutiveModel<dim> &model =
          *materials[grains[grain].material];
        const double old_plastic_strain = properties[Layout::plastic_strain];
        double       plastic_strain     = old_plastic_strain;
        const SymmetricTensor<2, 3> stress =
          model.update_stress(Layout::get_stress(properties),
                              increment,
                              plastic_strain);
        const double volume =
          store_particle_state(properties, stress, plastic_strain, increment);
        if (strain_energy != nullptr)
          *strain_energy += volume * model.strain_energy_density(stress);
        plastic_work +=
          volume *
          model.plastic_work_density(stress,
                                     plastic_strain - old_plastic_strain);
        if (force_array != nullptr)
          add_force(
            p, properties[Layout::mass], volume, stress, gravity, force_array);
      });
  }



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
    cache.for_each_entry(p, [&](const unsigned int e) {
      const unsigned int slot  = cache.slots[e];
      const double       shape = cache.shape_values[e];
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double v_new = new_values[slot * dim + d];
          interpolated[d] += shape * v_new;
          moved[d] += shape * position_values[slot * dim + d];
          increment[d] += shape * (v_new - reference_values[slot * dim + d]);
        }
    });
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
  std::pair<double, double>
  Transfer<dim>::grid_kinetic_changes(
    const VectorType      &masses,
    const VectorType      &new_velocities,
    const VectorType      &reference_velocities,
    const MassMatrix<dim> *mass_matrix) const
  {
    if (mass_matrix != nullptr && !mass_matrix->is_lumped())
      return {mass_matrix->local_kinetic_energy(new_velocities) -
                mass_matrix->local_kinetic_energy(reference_velocities),
              0.};
    double kinetic_change = 0., increment_energy = 0.;
    for (unsigned int s = 0; s < layout.n_slots(); ++s)
      if (!field_is_rigid[layout.field(s)])
        for (unsigned int d = 0; d < dim; ++d)
          {
            const unsigned int k      = s * dim + d;
            const double       v_new  = new_velocities.local_element(k);
            const double       v_old  = reference_velocities.local_element(k);
            const double       m_half = 0.5 * masses.local_element(s);
            kinetic_change += m_half * (v_new * v_new - v_old * v_old);
            increment_energy += m_half * (v_new - v_old) * (v_new - v_old);
          }
    return {kinetic_change, increment_energy};
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
    using Layout            = MaterialPointLayout<dim>;
    const Tensor<1, dim> &h = grid.cell_size();
    double                max_speed_square        = 0.;
    double                particle_kinetic_change = 0.;
    // sum_p 1/2 m_p |dv_p|^2 of the interpolated grid velocity change.
    double       particle_increment_energy = 0.;
    std::string  error;
    bool         error_from_rigid = false;
    ParticleSums sums;
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

        if (rigid)
          {
            // Rigid grains follow their prescribed velocity (midpoint rule).
            // A prescribed velocity that is not finite is the cause of any
            // other error: its message wins.
            if (std::string failure = rigid_motion.move_point(grain,
                                                              particle->get_id(),
                                                              old_position,
                                                              time,
                                                              dt,
                                                              new_position,
                                                              new_velocity);
                !failure.empty())
              {
                error            = std::move(failure);
                error_from_rigid = true;
                return;
              }
          }
        else
          {
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
            // A non-finite state, or a point that moves more than a cell
            // in one step: stop with the cause instead of carrying
            // nonsense on. A cheap test first (NaN fails every
            // comparison); the check decides and writes the message.
            bool suspicious = false;
            for (unsigned int d = 0; d < dim; ++d)
              suspicious =
                suspicious ||
                !(std::abs(new_velocity[d]) <=
                  std::numeric_limits<double>::max()) ||
                !(std::abs(new_position[d] - old_position[d]) <= h[d]);
            if (suspicious)
              if (const std::string failure =
                    update_check.check(particle->get_id(),
                                       grain,
                                       old_position,
                                       new_position,
                                       new_velocity,
                                       time,
                                       dt);
                  !failure.empty())
                {
                  if (error.empty())
                    error = failure;
                  return;
                }
          }
        Layout::set_velocity(new_velocity, properties);
        max_speed_square =
          std::max(max_speed_square, new_velocity.norm_square());

        bool removed = false;
        if (const std::string failure =
              update_check.leave_box(particle->get_id(),
                                     grain,
                                     rigid,
                                     new_position,
                                     time + dt,
                                     statistics.events.n_held_at_walls,
                                     removed);
            !failure.empty() || removed)
          {
            if (removed)
              particles_to_remove.push_back(particle);
            else if (error.empty())
              error = failure;
            return;
          }

        // Stay in the cell if possible: then no sort is needed.
        Point<dim> reference = particle->get_reference_location();
        bool       inside    = true;
        for (unsigned int d = 0; d < dim; ++d)
          {
            reference[d] += (new_position[d] - old_position[d]) / h[d];
            inside = inside && reference[d] >= 0. && reference[d] <= 1.;
          }
        if (options.gather_particle_sums && !rigid)
          {
            const double mass = properties[Layout::mass];
            sums.kinetic_energy += 0.5 * mass * new_velocity.norm_square();
            sums.elastic_energy +=
              properties[Layout::volume] *
              materials[grains[grain].material]->strain_energy_density(
                Layout::get_stress(properties));
            for (unsigned int d = 0; d < dim; ++d)
              {
                sums.momentum[d] += mass * new_velocity[d];
                sums.first_moment[d] += mass * new_position[d];
              }
          }
        particle->set_location(new_position);
        if (inside)
          particle->set_reference_location(reference);
        else
          statistics.events.sorted = true;
      });
    throw_on_all_ranks(error, grid.get_triangulation().get_communicator());
    statistics.events.max_speed = std::sqrt(max_speed_square);
    if (options.gather_particle_sums)
      {
        statistics.sums                   = sums;
        statistics.sums.has_particle_sums = true;
      }

    const auto [grid_kinetic_change, grid_increment_energy] =
      grid_kinetic_changes(masses, velocities_new, velocities_p2g, mass_matrix);
    statistics.ledger.transfer_energy_change =
      particle_kinetic_change - grid_kinetic_change;
    // The explicit leapfrog's kinetic-strain exchange misses the kinetic
    // energy of the grid-scale part of the step's velocity change (see
    // LedgerIncrements::leapfrog_energy_change).
    if (options.book_leapfrog_energy_change)
      statistics.ledger.leapfrog_energy_change =
        particle_increment_energy - grid_increment_energy;
  }



  template class Transfer<2>;
  template class Transfer<3>;
} // namespace grainmpm
