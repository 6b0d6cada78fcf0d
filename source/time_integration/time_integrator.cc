// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/time_integration/time_integrator.h>

#include <algorithm>

namespace grainmpm
{
  template <int dim>
  double
  largest_wave_speed(
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
  {
    double wave_speed = 0.;
    for (const auto &grain : grains)
      if (!grain.rigid)
        wave_speed =
          std::max(wave_speed, materials[grain.material]->wave_speed());
    return wave_speed;
  }



  template <int dim>
  void
  begin_step(Transfer<dim>                   &transfer,
             GrainContact<dim>               &contact,
             Particles::ParticleHandler<dim> &particle_handler,
             const double                     time,
             const double                     dt,
             GridState<dim>                  &state)
  {
    transfer.reinit(particle_handler);
    const GrainFieldLayout<dim> &layout = transfer.get_layout();
    state.node_in_contact.assign(layout.n_nodes(), 0);
    state.impulses.clear();
    // With one velocity field no node has several: no normals are needed.
    const bool normals = transfer.has_several_fields();
    transfer.particles_to_grid(particle_handler,
                               &state.masses,
                               state.momenta,
                               normals ? &state.mass_gradients : nullptr,
                               contact.uses_gaps() ? &state.volumes : nullptr,
                               &state.shape_sums);
    transfer.velocities_from_momenta(state.masses,
                                     state.momenta,
                                     state.velocities_p2g);
    contact.prescribe_rigid_velocities(layout, state.velocities_p2g, time);
    if (normals)
      {
        transfer.locate_rigid_grains(particle_handler, time, dt);
        contact.compute_normals(layout, state.mass_gradients, state.normals);
      }
    else
      layout.reinit_vector(state.normals, dim);
    if (contact.uses_gaps())
      contact.compute_gaps(
        layout, state.shape_sums, state.masses, state.volumes, dt);
  }



  template double
  largest_wave_speed<2>(
    const std::vector<GrainInfo<2>> &,
    const std::vector<std::unique_ptr<ConstitutiveModel<2>>> &);
  template double
  largest_wave_speed<3>(
    const std::vector<GrainInfo<3>> &,
    const std::vector<std::unique_ptr<ConstitutiveModel<3>>> &);
  template void
  begin_step<2>(Transfer<2> &,
                GrainContact<2> &,
                Particles::ParticleHandler<2> &,
                const double,
                const double,
                GridState<2> &);
  template void
  begin_step<3>(Transfer<3> &,
                GrainContact<3> &,
                Particles::ParticleHandler<3> &,
                const double,
                const double,
                GridState<3> &);
} // namespace grainmpm
