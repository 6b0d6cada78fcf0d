// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/theta_residual.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainmpm
{
  template <int dim>
  ThetaResidual<dim>::ThetaResidual(
    const GrainContact<dim>                                    &contact,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    : contact(contact)
    , grid(grid)
    , materials(materials)
  {}



  template <int dim>
  void
  ThetaResidual<dim>::reinit(
    const Transfer<dim>                   &transfer,
    const Particles::ParticleHandler<dim> &particle_handler,
    const MassMatrix<dim>                 &mass_matrix,
    const VectorType                      &masses,
    const VectorType                      &normals,
    const VectorType                      &old_velocities,
    const VectorType                      &rigid_velocities,
    const Tensor<1, dim>                  &gravity,
    const double                           theta,
    const double                           dt)
  {
    using Layout                              = MaterialPointLayout<dim>;
    this->transfer                            = &transfer;
    this->layout                              = &transfer.get_layout();
    this->mass_matrix                         = &mass_matrix;
    this->masses                              = &masses;
    this->normals                             = &normals;
    this->old_velocities                      = &old_velocities;
    this->rigid_velocities                    = &rigid_velocities;
    this->gravity                             = gravity;
    this->theta                               = theta;
    this->dt                                  = dt;
    const std::vector<GrainInfo<dim>> &grains = transfer.get_grains();

    // The particle mirror, in cache order.
    const std::size_t n_particles = transfer.get_cache().n_particles();
    particle_models.resize(n_particles);
    particle_rate_stresses.resize(n_particles);
    particle_volumes.resize(n_particles);
    particle_initial_volumes.resize(n_particles);
    particle_plastic_strains.resize(n_particles);
    transfer.for_each_particle(
      particle_handler, [&](const std::size_t p, const auto &particle) {
        const auto         properties = particle->get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        particle_models[p]            = grains[grain].rigid ?
                                          nullptr :
                                          materials[grains[grain].material].get();
        particle_volumes[p]           = properties[Layout::volume];
        particle_initial_volumes[p]   = properties[Layout::initial_volume];
        // The stress the model updates: J sigma (Kirchhoff) or sigma.
        if (particle_models[p] != nullptr)
          particle_rate_stresses[p] =
            particle_models[p]->rate_stress_factor(
              particle_volumes[p], particle_initial_volumes[p]) *
            Layout::get_stress(properties);
        particle_plastic_strains[p] = properties[Layout::plastic_strain];
      });

    // Unknowns: slots with a mass above 1e-6 of the largest particle mass
    // (MassMatrix::light_mass_threshold(); the mass matrix gives the other,
    // light, slots a lumped row); rigid slots are prescribed. A slot whose mass
    // is a round-off fraction of a point's (a point on a cell face) still has a
    // force of the point's size, grad S not being small: with a threshold of
    // 1e-12 such slots made the Newton solve of a disk in free fall fail (7
    // rejected steps in tests/implicit/energy_ledger_01), with 1e-9 and 1e-6 it
    // converges. The other slots only follow gravity, so that their points
    // (which they move by at most 1e-6 of their mass) are not strained by a
    // lag.
    mass_threshold = mass_matrix.light_mass_threshold();
    const std::vector<bool> &field_is_rigid = transfer.get_field_is_rigid();
    const unsigned int       n_slots        = layout->n_slots();
    slot_active.assign(n_slots, false);
    slot_rigid.assign(n_slots, false);
    for (unsigned int s = 0; s < n_slots; ++s)
      {
        slot_rigid[s]  = field_is_rigid[layout->field(s)];
        slot_active[s] = masses.local_element(s) > mass_threshold;
      }

    status.reinit(contact, *layout);
    ++status_generation;
    cached_generation = 0;
    // The contact inequality: the theta velocity approaches at most at the
    // speed that closes the gap within the step.
    status.keep_allowed_approach = true;
    preconditioner_pattern_stale = true;

    work_projected.reinit(old_velocities, true);
    work_theta.reinit(old_velocities, true);
    work_forces.reinit(old_velocities, true);
    if (!mass_matrix.is_lumped())
      {
        work_increment.reinit(old_velocities, true);
        work_inertia.reinit(old_velocities, true);
      }
  }



  template <int dim>
  NonlinearProblem::Change
  ThetaResidual<dim>::freeze_status(const VectorType &velocities,
                                    const bool        monotone)
  {
    // The decisions of a primal-dual active set (as in deal.II's step-41):
    // a held slot on its reaction, a free slot on its motion. A held slot
    // stays held while the theta velocity of what the momentum balance
    // asks for, V - R_raw(V) = v^n + dt (f / m + g) (the explicit scheme's
    // v^L), approaches by more than the constraint lets it (the reaction
    // pushes), and is released when it would pull. A free slot is caught
    // when its own theta velocity (1 - theta) v^n + theta V passes the
    // approach its gap allows. For a free slot both velocities agree once
    // the solve has converged, but at an early iterate of a long step
    // V - R_raw(V) carries the iterate's error amplified by about
    // (dt / dt_explicit)^2: decided on it, slots were caught and released in
    // turn until they settled free, and grains passed into each other. The
    // first decision of a step, with no status yet, is taken on
    // V - R_raw(V) for every slot.
    VectorType trial_velocities(velocities);
    {
      VectorType raw;
      raw.reinit(velocities, true);
      raw_residual_at(velocities, raw);
      trial_velocities -= raw;
      trial_velocities.sadd(theta, 1. - theta, *old_velocities);
    }
    if (status.decided)
      {
        std::vector<bool> held(layout->n_slots(), false);
        for (unsigned int s = 0; s < held.size(); ++s)
          held[s] = status.slot_state[s] != ContactState::free;
        for (unsigned int w = 0; w < status.wall_slots.size(); ++w)
          if (status.wall_state[w] != ContactState::free)
            held[status.wall_slots[w]] = true;
        for (unsigned int s = 0; s < held.size(); ++s)
          if (!held[s])
            for (unsigned int d = 0; d < dim; ++d)
              trial_velocities.local_element(s * dim + d) =
                (1. - theta) * old_velocities->local_element(s * dim + d) +
                theta * velocities.local_element(s * dim + d);
      }

    const ContactStatus<dim> old_status = status;
    status.freeze(contact,
                  *layout,
                  *masses,
                  *normals,
                  trial_velocities,
                  mass_threshold,
                  status_band,
                  !monotone);
    // A new generation unless the status evaluate() applies is the same
    // (the frozen v_ref enters only the simplified map, which is not
    // cached).
    if (old_status.slot_state != status.slot_state ||
        old_status.slip_directions != status.slip_directions ||
        old_status.slot_kept != status.slot_kept ||
        old_status.wall_state != status.wall_state ||
        old_status.wall_slip_directions != status.wall_slip_directions ||
        old_status.wall_kept != status.wall_kept)
      ++status_generation;
    // The change on any rank (the solver's decisions must agree): the
    // number of slots and wall entries whose discrete state changed, or
    // whether a slip direction did.
    const auto n_differences = [](const auto &a, const auto &b) {
      if (a.size() != b.size())
        return static_cast<unsigned int>(std::max(a.size(), b.size()));
      unsigned int n = 0;
      for (std::size_t k = 0; k < a.size(); ++k)
        n += (a[k] != b[k]);
      return n;
    };
    const unsigned int n_changed = Utilities::MPI::sum(
      n_differences(old_status.slot_state, status.slot_state) +
        n_differences(old_status.wall_state, status.wall_state),
      communicator());
    if (n_changed > max_minor_status_change)
      return Change::discrete;
    if (n_changed > 0)
      return Change::minor;
    const unsigned int continuous =
      (old_status.slip_directions != status.slip_directions ||
       old_status.wall_slip_directions != status.wall_slip_directions) ?
        1 :
        0;
    return Utilities::MPI::max(continuous, communicator()) > 0 ?
             Change::continuous :
             Change::none;
  }



  template <int dim>
  std::string
  ThetaResidual<dim>::why_not_finite() const
  {
    if (Utilities::MPI::max(last_evaluation_inverted ? 1U : 0U,
                            communicator()) == 0)
      return "";
    return "a material point inverts (det(I + dt grad v^theta) <= 0)";
  }



  template <int dim>
  void
  ThetaResidual<dim>::setup_preconditioner(const VectorType &)
  {
    std::vector<bool> unknown(layout->n_slots());
    for (unsigned int s = 0; s < unknown.size(); ++s)
      unknown[s] = slot_active[s] && !slot_rigid[s];
    preconditioner.setup(
      *layout,
      unknown,
      *masses,
      [this](VectorType &v) {
        status.apply_symmetric_linear_part(
          contact, *layout, *masses, *normals, v);
      },
      transfer->get_cache(),
      particle_models,
      particle_volumes,
      *mass_matrix,
      theta * theta * dt * dt,
      *old_velocities,
      preconditioner_pattern_stale);
    preconditioner_pattern_stale = false;
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::project(const VectorType           &velocities,
                              VectorType                 &projected,
                              std::vector<unsigned char> *node_in_contact,
                              ConstraintImpulses<dim>    *impulses) const
  {
    copy_slot_vector(velocities, projected);
    return apply_projection(projected, false, node_in_contact, impulses);
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::apply_projection(
    VectorType                 &v,
    const bool                  simplified,
    std::vector<unsigned char> *node_in_contact,
    ConstraintImpulses<dim>    *impulses) const
  {
    // v -> (1 - theta) v^n + theta v, project, and back. The map is affine
    // (its linear part, on differences of velocities, is
    // ContactStatus::apply_simplified_linear_part()). With every slot free
    // it is the identity.
    if (!status.any_active)
      return 0;
    const unsigned int n = v.locally_owned_size();
    for (unsigned int k = 0; k < n; ++k)
      v.local_element(k) = (1. - theta) * old_velocities->local_element(k) +
                           theta * v.local_element(k);
    // The projection changes the theta velocity; the end velocity changes
    // by that over theta.
    if (impulses != nullptr)
      impulses->scale = 1. / theta;
    const unsigned int n_active =
      simplified ?
        status.apply_simplified(contact, *layout, *masses, *normals, v) :
        status.apply(
          contact, *layout, *masses, *normals, v, node_in_contact, impulses);
    if (impulses != nullptr)
      impulses->scale = 1.;
    for (unsigned int k = 0; k < n; ++k)
      v.local_element(k) =
        (v.local_element(k) - (1. - theta) * old_velocities->local_element(k)) /
        theta;
    return n_active;
  }



  template <int dim>
  void
  ThetaResidual<dim>::theta_velocities(const VectorType &projected,
                                       VectorType       &theta_v) const
  {
    const unsigned int n = projected.locally_owned_size();
    for (unsigned int k = 0; k < n; ++k)
      theta_v.local_element(k) =
        (1. - theta) * old_velocities->local_element(k) +
        theta * projected.local_element(k);
  }



  template <int dim>
  void
  ThetaResidual<dim>::evaluate(const VectorType &velocities,
                               VectorType       &residual,
                               const bool        simplified,
                               const bool        raw) const
  {
    ++evaluation_count;

    // v^theta from the projected trial velocities.
    work_projected = velocities;
    const bool constrained =
      apply_projection(work_projected, simplified, nullptr) > 0 ||
      !status.wall_slots.empty();
    theta_velocities(work_projected, work_theta);
    work_theta.update_ghost_values();
    const bool inverted      = assemble_internal_forces();
    last_evaluation_inverted = inverted;
    work_theta.zero_out_ghost_values();
    // M (V - v^n), before the return on inverted particles: it is
    // collective.
    if (!mass_matrix->is_lumped())
      {
        const unsigned int n = velocities.locally_owned_size();
        for (unsigned int k = 0; k < n; ++k)
          work_increment.local_element(k) =
            velocities.local_element(k) - old_velocities->local_element(k);
        mass_matrix->vmult(work_inertia, work_increment);
      }
    cached_generation = 0;
    if (inverted)
      {
        // NaN on this rank makes every rank's norm NaN.
        residual = std::numeric_limits<double>::quiet_NaN();
        return;
      }

    raw_residual(velocities, residual);
    if (!simplified)
      {
        cached_raw_residual = residual;
        cached_velocities   = velocities;
        cached_generation   = status_generation;
      }
    if (raw || !constrained)
      return;
    constrain_residual(velocities, residual, simplified);
  }



  template <int dim>
  void
  ThetaResidual<dim>::raw_residual_at(const VectorType &velocities,
                                      VectorType       &raw) const
  {
    // The decision is collective: evaluate() is.
    const unsigned int n      = velocities.locally_owned_size();
    const bool         cached = cached_generation == status_generation &&
                        cached_velocities.locally_owned_size() == n &&
                        std::equal(velocities.begin(),
                                   velocities.begin() + n,
                                   cached_velocities.begin());
    if (Utilities::MPI::min(cached ? 1U : 0U, communicator()) == 1U)
      raw = cached_raw_residual;
    else
      evaluate(velocities, raw, false, true);
  }



  template <int dim>
  bool
  ThetaResidual<dim>::assemble_internal_forces() const
  {
    // Internal forces from the time-centred stress and volume (eqs. 12-13),
    // on raw pointers and local copies of theta and dt: stores into the
    // forces could otherwise alias them, and they would be reloaded for
    // every particle.
    work_forces                      = 0.;
    bool                inverted     = false;
    const double        theta_local  = theta;
    const double        dt_local     = dt;
    const double *const theta_values = work_theta.begin();
    double *const       forces       = work_forces.begin();
    const std::size_t   n_particles  = particle_models.size();
    for (std::size_t p = 0; p < n_particles; ++p)
      {
        const ConstitutiveModel<dim> *const model = particle_models[p];
        if (model == nullptr)
          continue;
        // dt grad v^theta.
        Tensor<2, dim> increment = transfer->velocity_gradient(p, theta_values);
        increment *= dt_local;
        double plastic_strain                   = particle_plastic_strains[p];
        const SymmetricTensor<2, 3> &old_stress = particle_rate_stresses[p];
        const SymmetricTensor<2, 3>  new_stress =
          model->update_stress(old_stress, increment, plastic_strain);

        // V^theta sigma^theta in the plane (V0 tau^theta with the Kirchhoff
        // stress). A trial that inverts a particle
        // (det(I + dt grad v) <= 0) has no meaning: its residual is NaN,
        // which the line search and the failure policy reject.
        double jacobian;
        if constexpr (dim == 2)
          jacobian = (1. + increment[0][0]) * (1. + increment[1][1]) -
                     increment[0][1] * increment[1][0];
        else
          jacobian = determinant(unit_symmetric_tensor<dim>() + increment);
        if (!(jacobian > 0.))
          inverted = true;
        const double volume =
          model->energy_volume(particle_volumes[p] *
                                 ((1. - theta_local) + theta_local * jacobian),
                               particle_initial_volumes[p]);
        double stress[dim][dim];
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            {
              const unsigned int k =
                SymmetricTensor<2, 3>::component_to_unrolled_index(
                  TableIndices<2>(i, j));
              stress[i][j] = stress[j][i] =
                volume * ((1. - theta_local) * old_stress.access_raw_entry(k) +
                          theta_local * new_stress.access_raw_entry(k));
            }
        transfer->subtract_divergence(p, stress, forces);
      }
    work_forces.compress(VectorOperation::add);
    return inverted;
  }



  template <int dim>
  void
  ThetaResidual<dim>::raw_residual(const VectorType &velocities,
                                   VectorType       &residual) const
  {
    // R = V - v^n - dt (f / m + g), in velocity units; with the blended
    // mass, M (V - v^n) / m in place of V - v^n. Slots too light to carry
    // a force fall with gravity.
    const unsigned int n_slots = layout->n_slots();
    const bool         lumped  = mass_matrix->is_lumped();
    for (unsigned int s = 0; s < n_slots; ++s)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const unsigned int k = s * dim + d;
          if (slot_rigid[s])
            {
              residual.local_element(k) = velocities.local_element(k) -
                                          rigid_velocities->local_element(k);
              continue;
            }
          const double inertia =
            lumped ?
              velocities.local_element(k) - old_velocities->local_element(k) :
              work_inertia.local_element(k) / masses->local_element(s);
          const double acceleration =
            slot_active[s] ?
              work_forces.local_element(k) / masses->local_element(s) :
              0.;
          residual.local_element(k) =
            inertia - dt * (acceleration + gravity[d]);
        }
  }



  template <int dim>
  void
  ThetaResidual<dim>::constrain_residual(const VectorType &velocities,
                                         VectorType       &residual,
                                         const bool        simplified) const
  {
    // Constrained form R = P R_raw + (V - P V): the frozen projection P is
    // the mass-orthogonal projection onto the velocities that satisfy the
    // active contacts and walls (with friction, its sliding variant), so
    // the reactions take the component of R_raw that P removes and the
    // converged V satisfies the constraints itself. Then theta = 1/2
    // conserves energy through persistent contact, which R_raw with P V only in
    // the stress does not.
    work_forces = residual;
    if (simplified)
      status.apply_simplified_linear_part(
        contact, *layout, *masses, *normals, work_forces);
    else
      apply_projection(work_forces, false, nullptr);
    const unsigned int n = residual.locally_owned_size();
    for (unsigned int k = 0; k < n; ++k)
      residual.local_element(k) = work_forces.local_element(k) +
                                  velocities.local_element(k) -
                                  work_projected.local_element(k);
  }



  template <int dim>
  double
  ThetaResidual<dim>::old_strain_energy() const
  {
    double energy = 0.;
    for (std::size_t p = 0; p < particle_models.size(); ++p)
      if (particle_models[p] != nullptr)
        energy +=
          particle_models[p]->energy_volume(particle_volumes[p],
                                            particle_initial_volumes[p]) *
          particle_models[p]->strain_energy_density(particle_rate_stresses[p]);
    return energy;
  }



  template class ThetaResidual<2>;
  template class ThetaResidual<3>;
} // namespace grainmpm
