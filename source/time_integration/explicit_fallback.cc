// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/explicit_fallback.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  namespace
  {
    /**
     * The run's parameters with the explicit scheme's settings of the
     * fallback: update stress last, lumped mass.
     */
    template <int dim>
    Parameters<dim>
    fallback_parameters(const Parameters<dim> &parameters)
    {
      Parameters<dim>         explicit_parameters = parameters;
      TimeSteppingParameters &time_stepping = explicit_parameters.time_stepping;
      time_stepping.scheme        = TimeSteppingScheme::explicit_leapfrog;
      time_stepping.stress_update = StressUpdate::usl;
      time_stepping.mass_matrix   = MassMatrixType::lumped;
      time_stepping.consistent_mass_fraction = 0.;
      return explicit_parameters;
    }



    /** Add the statistics @p step of a sub-step to those of its step. */
    void
    add_substep(const StepStatistics &step, StepStatistics &total)
    {
      total.events.n_contact_nodes =
        std::max(total.events.n_contact_nodes, step.events.n_contact_nodes);
      total.events.n_removed += step.events.n_removed;
      total.events.n_held_at_walls += step.events.n_held_at_walls;
      total.events.max_speed = step.events.max_speed;
      total.events.sorted    = total.events.sorted || step.events.sorted;

      total.ledger.grid_energy_change += step.ledger.grid_energy_change;
      total.ledger.transfer_energy_change += step.ledger.transfer_energy_change;
      total.ledger.plastic_work += step.ledger.plastic_work;
      total.ledger.friction_work += step.ledger.friction_work;
      total.ledger.boundary_work += step.ledger.boundary_work;
      total.ledger.leapfrog_energy_change += step.ledger.leapfrog_energy_change;
      total.ledger.hypoelastic_correction += step.ledger.hypoelastic_correction;

      // The particle sums, where gathered, are those after the last one.
      total.sums = step.sums;
      ++total.solver.explicit_substeps;
    }
  } // namespace



  template <int dim>
  ExplicitFallback<dim>::ExplicitFallback(
    const Parameters<dim>                                      &parameters,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    : parameters(fallback_parameters(parameters))
    , communicator(grid.get_triangulation().get_communicator())
    , minimum_cell_size(grid.minimum_cell_size())
    , wave_speed(largest_wave_speed(grains, materials))
    , leapfrog(std::make_unique<ExplicitLeapfrog<dim>>(this->parameters,
                                                       grid,
                                                       grains,
                                                       materials))
  {}



  template <int dim>
  double
  ExplicitFallback<dim>::stable_step(
    const Particles::ParticleHandler<dim> &particle_handler) const
  {
    double max_speed = 0.;
    for (const auto &particle : particle_handler)
      max_speed = std::max(max_speed,
                           MaterialPointLayout<dim>::get_velocity(
                             particle.get_properties())
                             .norm());
    max_speed = Utilities::MPI::max(max_speed, communicator);
    return minimum_cell_size / (wave_speed + max_speed);
  }



  template <int dim>
  StepStatistics
  ExplicitFallback<dim>::advance(
    Particles::ParticleHandler<dim> &particle_handler,
    const double                     time,
    const double                     interval)
  {
    StepStatistics total;
    impulses.clear();
    double step = 0.25 * stable_step(particle_handler);
    double done = 0.;
    while (done < interval)
      {
        // Equal sub-steps over what is left, none above a quarter of the
        // stable step of the particles' current speeds.
        const double left = interval - done;
        const auto   n =
          static_cast<unsigned int>(std::max(1., std::ceil(left / step)));
        const double         dt = (n == 1 ? left : left / n);
        const StepStatistics sub =
          leapfrog->advance(particle_handler, time + done, dt);
        add_substep(sub, total);
        const ConstraintImpulses<dim> &step_impulses = leapfrog->get_impulses();
        impulses.scale                               = step_impulses.scale;
        for (unsigned int f = 0; f < impulses.walls.size(); ++f)
          impulses.walls[f] += step_impulses.walls[f];
        impulses.pairs.insert(impulses.pairs.end(),
                              step_impulses.pairs.begin(),
                              step_impulses.pairs.end());
        done = (n == 1 ? interval : done + dt);
        step = 0.25 * minimum_cell_size / (wave_speed + sub.events.max_speed);
      }
    return total;
  }



  template class ExplicitFallback<2>;
  template class ExplicitFallback<3>;
} // namespace grainmpm
