// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/explicit_leapfrog.h>

#include <deal.II/lac/vector.h>


namespace grainmpm
{
  template <int dim>
  ExplicitLeapfrog<dim>::ExplicitLeapfrog(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    : TimeIntegrator<dim>(parameters, grid, grains, materials)
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
    this->begin_step(particle_handler, time);

    copy_slot_vector(velocities_p2g, velocities_old);
    if (parameters.time_stepping.stress_update == StressUpdate::usf)
      {
        // Eqs. (8)-(10): strain from the (contact-corrected) v^n, then the
        // forces of eq. (7) from sigma^{n+1/2}, V^{n+1/2}.
        statistics.n_contact_nodes += apply_constraints(velocities_old);
        update_stresses(particle_handler,
                        velocities_old,
                        dt,
                        statistics.plastic_work);
        compute_forces(particle_handler);
      }
    else
      compute_forces(particle_handler);

    integrate_grid_velocities(dt);
    copy_slot_vector(velocities_new, unconstrained_velocities);
    statistics.n_contact_nodes += apply_constraints(velocities_new);
    this->add_constraint_work(unconstrained_velocities,
                              velocities_new,
                              velocities_new,
                              statistics);
    prescribe_rigid_velocities(velocities_new, time + dt);

    this->grid_to_particles(
      particle_handler, velocities_new, time, dt, statistics);

    if (parameters.time_stepping.stress_update == StressUpdate::musl)
      {
        remap_velocities(particle_handler);
        prescribe_rigid_velocities(velocities_old, time + dt);
        statistics.n_contact_nodes += apply_constraints(velocities_old);
        update_stresses(particle_handler,
                        velocities_old,
                        dt,
                        statistics.plastic_work);
      }

    this->finish_step(particle_handler, statistics);
    return statistics;
  }



  template <int dim>
  void
  ExplicitLeapfrog<dim>::update_stresses(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &grid_velocities,
    const double                     dt,
    double                          &plastic_work)
  {
    using Layout = MaterialPointLayout<dim>;
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    grid_velocities.update_ghost_values();

    std::size_t p = 0;
    for_each_particle(
      grid, particle_handler, [&](const auto &, auto &particle) {
        const unsigned int offset = p * per_particle;
        ++p;
        auto               properties = particle->get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        if (grains[grain].rigid)
          return;

        // dt L_p = dt sum_i v_i (x) grad S_ip (eq. 8 before symmetrisation).
        Tensor<2, dim> increment;
        for (unsigned int v = 0; v < per_particle; ++v)
          {
            const unsigned int    slot     = cache.slots[offset + v];
            const Tensor<1, dim> &gradient = cache.shape_gradients[offset + v];
            for (unsigned int i = 0; i < dim; ++i)
              {
                const double velocity =
                  grid_velocities.local_element(slot * dim + i);
                for (unsigned int j = 0; j < dim; ++j)
                  increment[i][j] += velocity * gradient[j];
              }
          }
        increment *= dt;

        // Eq. (9) through the constitutive model; F and eq. (10) for V.
        const ConstitutiveModel<dim> &model =
          *materials[grains[grain].material];
        const double old_plastic_strain = properties[Layout::plastic_strain];
        double       plastic_strain     = old_plastic_strain;
        const SymmetricTensor<2, 3> stress =
          model.update_stress(Layout::get_stress(properties),
                              increment,
                              plastic_strain);
        const double volume = this->store_particle_state(properties,
                                                         stress,
                                                         plastic_strain,
                                                         increment);
        plastic_work +=
          volume *
          model.plastic_work_density(stress,
                                     plastic_strain - old_plastic_strain);
      });
  }



  template <int dim>
  void
  ExplicitLeapfrog<dim>::compute_forces(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    using Layout = MaterialPointLayout<dim>;
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    const Tensor<1, dim> &gravity = parameters.physics.gravity;
    layout.reinit_vector(forces, dim);

    std::size_t p = 0;
    for_each_particle(
      grid, particle_handler, [&](const auto &, auto &particle) {
        const unsigned int offset = p * per_particle;
        ++p;
        const auto properties = particle->get_properties();
        if (grains[Layout::get_grain(properties)].rigid)
          return;
        const double                mass   = properties[Layout::mass];
        const double                volume = properties[Layout::volume];
        const SymmetricTensor<2, 3> stress = Layout::get_stress(properties);
        for (unsigned int v = 0; v < per_particle; ++v)
          {
            const unsigned int    slot     = cache.slots[offset + v];
            const double          shape    = cache.shape_values[offset + v];
            const Tensor<1, dim> &gradient = cache.shape_gradients[offset + v];
            for (unsigned int i = 0; i < dim; ++i)
              {
                double divergence = 0.;
                for (unsigned int j = 0; j < dim; ++j)
                  divergence += stress[i][j] * gradient[j];
                forces.local_element(slot * dim + i) +=
                  -volume * divergence + mass * shape * gravity[i];
              }
          }
      });
    forces.compress(VectorOperation::add);
  }



  template <int dim>
  void
  ExplicitLeapfrog<dim>::integrate_grid_velocities(const double dt)
  {
    copy_slot_vector(velocities_old, velocities_new);
    for (unsigned int slot = 0; slot < layout.n_slots(); ++slot)
      {
        const double mass = masses.local_element(slot);
        if (mass > 0. && !field_is_rigid[layout.field(slot)])
          for (unsigned int d = 0; d < dim; ++d)
            velocities_new.local_element(slot * dim + d) +=
              dt * forces.local_element(slot * dim + d) / mass;
      }
  }



  template <int dim>
  void
  ExplicitLeapfrog<dim>::remap_velocities(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    using Layout = MaterialPointLayout<dim>;
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    layout.reinit_vector(momenta, dim);
    std::size_t p = 0;
    for_each_particle(grid,
                      particle_handler,
                      [&](const auto &, auto &particle) {
                        const unsigned int offset = p * per_particle;
                        ++p;
                        const auto   properties = particle->get_properties();
                        const double mass       = properties[Layout::mass];
                        for (unsigned int v = 0; v < per_particle; ++v)
                          {
                            const unsigned int slot = cache.slots[offset + v];
                            const double shape = cache.shape_values[offset + v];
                            for (unsigned int d = 0; d < dim; ++d)
                              momenta.local_element(slot * dim + d) +=
                                mass * shape * properties[Layout::velocity + d];
                          }
                      });
    momenta.compress(VectorOperation::add);
    velocities_from_momenta(velocities_old);
  }



  template class ExplicitLeapfrog<2>;
  template class ExplicitLeapfrog<3>;
} // namespace grainmpm
