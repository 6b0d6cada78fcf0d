// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/time_integration/theta_residual.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainmpm
{
  template <int dim>
  ThetaResidual<dim>::ThetaResidual(
    const ContactParameters                                    &contact,
    const BackgroundGrid<dim>                                  &grid,
    const std::vector<bool>                                    &field_is_rigid,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials)
    : contact(contact)
    , grid(grid)
    , field_is_rigid(field_is_rigid)
    , materials(materials)
  {}



  template <int dim>
  void
  ThetaResidual<dim>::reinit(
    const TransferCache<dim>              &cache,
    const GrainFieldLayout<dim>           &layout,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<GrainInfo<dim>>     &grains,
    const VectorType                      &masses,
    const VectorType                      &normals,
    const VectorType                      &old_velocities,
    const VectorType                      &rigid_velocities,
    const Tensor<1, dim>                  &gravity,
    const double                           theta,
    const double                           dt)
  {
    using Layout           = MaterialPointLayout<dim>;
    this->cache            = &cache;
    this->layout           = &layout;
    this->masses           = &masses;
    this->normals          = &normals;
    this->old_velocities   = &old_velocities;
    this->rigid_velocities = &rigid_velocities;
    this->gravity          = gravity;
    this->theta            = theta;
    this->dt               = dt;

    // The particle mirror, in cache order.
    const std::size_t n_particles = cache.n_particles();
    particle_models.resize(n_particles);
    particle_stresses.resize(n_particles);
    particle_volumes.resize(n_particles);
    particle_plastic_strains.resize(n_particles);
    double      largest_mass = 0.;
    std::size_t p            = 0;
    for_each_particle(
      grid, particle_handler, [&](const auto &, const auto &particle) {
        const auto         properties = particle->get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        particle_models[p]            = grains[grain].rigid ?
                                          nullptr :
                                          materials[grains[grain].material].get();
        particle_stresses[p]          = Layout::get_stress(properties);
        particle_volumes[p]           = properties[Layout::volume];
        particle_plastic_strains[p]   = properties[Layout::plastic_strain];
        largest_mass = std::max(largest_mass, properties[Layout::mass]);
        ++p;
      });
    largest_mass = Utilities::MPI::max(largest_mass, communicator());

    // Unknowns: slots with a mass above 1e-6 of the largest particle mass
    // (m_min of reference/physics.md section 8.5); rigid slots are
    // prescribed. A slot whose mass is a round-off fraction of a point's
    // (a point on a cell face) still has a force of the point's size, grad
    // S not being small: with a threshold of 1e-12 such slots made the
    // Newton solve of a disk in free fall fail (7 rejected steps in
    // tests/implicit/energy_ledger_01), with 1e-9 and 1e-6 it converges.
    // The other slots only follow gravity, so that their points (which they
    // move by at most 1e-6 of their mass) are not strained by a lag.
    const unsigned int n_slots = layout.n_slots();
    slot_active.assign(n_slots, false);
    slot_rigid.assign(n_slots, false);
    for (unsigned int s = 0; s < n_slots; ++s)
      {
        slot_rigid[s]  = field_is_rigid[layout.field(s)];
        slot_active[s] = masses.local_element(s) > 1e-6 * largest_mass;
      }

    // Wall entries: (slot, face) of deformable slots at closed faces.
    wall_slots.clear();
    wall_faces.clear();
    for (const unsigned int node : grid.boundary_nodes())
      {
        const unsigned int faces = grid.node_faces(node);
        for (unsigned int s = layout.node_slots_begin(node);
             s < layout.node_slots_end(node);
             ++s)
          if (!slot_rigid[s])
            for (unsigned int face = 0; face < 2 * dim; ++face)
              if ((faces & (1U << face)) &&
                  grid.boundary_condition(face).type != BoundaryType::open)
                {
                  wall_slots.push_back(s);
                  wall_faces.push_back(face);
                }
      }

    slot_state.assign(n_slots, free);
    slip_directions.assign(n_slots, Tensor<1, dim>());
    frozen_references.assign(n_slots, Tensor<1, dim>());
    wall_state.assign(wall_slots.size(), free);
    any_constraint_active = false;
    wall_slip_directions.assign(wall_slots.size(), Tensor<1, dim>());

    work_projected.reinit(old_velocities, true);
    work_theta.reinit(old_velocities, true);
    work_forces.reinit(old_velocities, true);
  }



  template <int dim>
  unsigned char
  ThetaResidual<dim>::classify(const Tensor<1, dim> &relative,
                               const Tensor<1, dim> &normal,
                               const double          mu,
                               Tensor<1, dim>       &slip_direction)
  {
    // The decisions of GrainContact::project_node() and apply_wall():
    // approaching iff relative . n > 0; then stick if mu D >= |v_t|.
    slip_direction        = Tensor<1, dim>();
    const double approach = relative * normal;
    if (!(approach > 0.))
      return free;
    const Tensor<1, dim> tangential = relative - approach * normal;
    const double         slip       = tangential.norm();
    if (mu > 0. && mu * approach >= slip)
      return sticking;
    if (mu > 0.)
      slip_direction = tangential / slip;
    return sliding;
  }



  template <int dim>
  NonlinearProblem::Change
  ThetaResidual<dim>::freeze_status(const VectorType &velocities)
  {
    // Contact is detected on the theta velocity of what the momentum
    // balance asks for, V - R_raw(V) = v^n + dt (f / m + g) (the explicit
    // scheme's v^L): a slot held by a constraint stays held while its
    // reaction pushes, and is released when it would pull (active-set
    // Newton).
    VectorType trial_velocities(velocities);
    {
      VectorType raw;
      raw.reinit(velocities, true);
      evaluate(velocities, raw, false, true);
      trial_velocities -= raw;
      trial_velocities.sadd(theta, 1. - theta, *old_velocities);
    }

    const std::vector<unsigned char>  old_slot_state      = slot_state;
    const std::vector<unsigned char>  old_wall_state      = wall_state;
    const std::vector<Tensor<1, dim>> old_slip_directions = slip_directions;
    const std::vector<Tensor<1, dim>> old_wall_directions =
      wall_slip_directions;
    const double mu = (contact.model == ContactModel::coulomb_friction) ?
                        contact.friction_coefficient :
                        0.;

    // Contact: the decisions of GrainContact::project_node() at V.
    std::fill(slot_state.begin(), slot_state.end(), free);
    for (const unsigned int node : layout->contact_nodes())
      {
        const unsigned int begin = layout->node_slots_begin(node);
        const unsigned int end   = layout->node_slots_end(node);
        Tensor<1, dim>     reference, momentum;
        double             total_mass = 0.;
        int                rigid_slot = -1;
        for (unsigned int s = begin; s < end; ++s)
          if (slot_rigid[s])
            rigid_slot = (rigid_slot < 0) ? static_cast<int>(s) : rigid_slot;
          else
            {
              total_mass += masses->local_element(s);
              momentum += masses->local_element(s) *
                          get_slot_vector<dim>(trial_velocities, s);
            }
        if (rigid_slot >= 0)
          reference = get_slot_vector<dim>(trial_velocities, rigid_slot);
        else if (total_mass > 0.)
          reference = momentum / total_mass;
        for (unsigned int s = begin; s < end; ++s)
          {
            frozen_references[s] = reference;
            slip_directions[s]   = Tensor<1, dim>();
            if (slot_rigid[s] || !slot_active[s])
              continue;
            if (contact.model == ContactModel::none)
              {
                if (rigid_slot >= 0)
                  slot_state[s] = sticking;
                continue;
              }
            const Tensor<1, dim> normal = get_slot_vector<dim>(*normals, s);
            if (normal.norm_square() == 0.)
              continue;
            slot_state[s] =
              classify(get_slot_vector<dim>(trial_velocities, s) - reference,
                       normal,
                       mu,
                       slip_directions[s]);
          }
      }

    // Walls see the velocities after contact, face after face.
    work_projected = trial_velocities;
    apply_frozen_contact(work_projected, ReferenceMode::from_vector, nullptr);
    for (unsigned int w = 0; w < wall_slots.size(); ++w)
      {
        const unsigned int       s = wall_slots[w];
        const BoundaryCondition &condition =
          grid.boundary_condition(wall_faces[w]);
        const Tensor<1, dim> normal =
          GrainContact<dim>::face_normal(wall_faces[w]);
        Tensor<1, dim> velocity = get_slot_vector<dim>(work_projected, s);
        wall_slip_directions[w] = Tensor<1, dim>();
        if (condition.type == BoundaryType::no_slip)
          wall_state[w] = sticking;
        else
          wall_state[w] = classify(velocity,
                                   normal,
                                   (condition.type == BoundaryType::friction) ?
                                     condition.friction_coefficient :
                                     0.,
                                   wall_slip_directions[w]);
        apply_wall_entry(w, velocity);
        set_slot_vector<dim>(velocity, work_projected, s);
      }
    any_constraint_active =
      std::any_of(slot_state.begin(),
                  slot_state.end(),
                  [](const unsigned char state) { return state != free; }) ||
      std::any_of(wall_state.begin(),
                  wall_state.end(),
                  [](const unsigned char state) { return state != free; });
    // The change on any rank (the solver's decisions must agree).
    unsigned int change = 0;
    if (old_slot_state != slot_state || old_wall_state != wall_state)
      change = static_cast<unsigned int>(Change::discrete);
    else if (old_slip_directions != slip_directions ||
             old_wall_directions != wall_slip_directions)
      change = static_cast<unsigned int>(Change::continuous);
    return static_cast<Change>(Utilities::MPI::max(change, communicator()));
  }



  template <int dim>
  void
  ThetaResidual<dim>::jacobian_diagonal(const VectorType   &x,
                                        const StepFunction &step,
                                        VectorType         &diagonal)
  {
    VectorType simplified_residual;
    simplified_residual.reinit(x, true);
    evaluate(x, simplified_residual, true);
    probe_diagonal(x, simplified_residual, diagonal, step);
  }



  template <int dim>
  void
  ThetaResidual<dim>::apply_wall_entry(const unsigned int w,
                                       Tensor<1, dim>    &velocity) const
  {
    if (wall_state[w] == sticking)
      velocity = 0.;
    else if (wall_state[w] == sliding)
      {
        const BoundaryCondition &condition =
          grid.boundary_condition(wall_faces[w]);
        const Tensor<1, dim> normal =
          GrainContact<dim>::face_normal(wall_faces[w]);
        const double approach = velocity * normal;
        const double mu       = (condition.type == BoundaryType::friction) ?
                                  condition.friction_coefficient :
                                  0.;
        velocity -=
          approach * normal + (mu * approach) * wall_slip_directions[w];
      }
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::apply_frozen_contact(
    VectorType                 &v,
    const ReferenceMode         mode,
    std::vector<unsigned char> *node_flags) const
  {
    const double mu       = (contact.model == ContactModel::coulomb_friction) ?
                              contact.friction_coefficient :
                              0.;
    unsigned int n_active = 0;
    for (const unsigned int node : layout->contact_nodes())
      {
        const unsigned int begin = layout->node_slots_begin(node);
        const unsigned int end   = layout->node_slots_end(node);
        bool               any   = false;
        for (unsigned int s = begin; s < end; ++s)
          any = any || (slot_state[s] != free);
        if (!any)
          continue;
        ++n_active;
        if (node_flags != nullptr)
          (*node_flags)[node] = 1;

        Tensor<1, dim> reference, momentum_before;
        double         total_mass   = 0.;
        int            rigid_slot   = -1;
        unsigned int   n_deformable = 0;
        for (unsigned int s = begin; s < end; ++s)
          if (slot_rigid[s])
            rigid_slot = (rigid_slot < 0) ? static_cast<int>(s) : rigid_slot;
          else
            {
              total_mass += masses->local_element(s);
              momentum_before +=
                masses->local_element(s) * get_slot_vector<dim>(v, s);
              ++n_deformable;
            }
        const bool simplified = (mode != ReferenceMode::from_vector);
        if (mode == ReferenceMode::frozen)
          reference = frozen_references[begin];
        else if (mode == ReferenceMode::zero)
          reference = Tensor<1, dim>();
        else if (rigid_slot >= 0)
          reference = get_slot_vector<dim>(v, rigid_slot);
        else
          reference = momentum_before / total_mass;

        for (unsigned int s = begin; s < end; ++s)
          if (slot_state[s] == sticking)
            set_slot_vector<dim>(reference, v, s);
          else if (slot_state[s] == sliding)
            {
              const Tensor<1, dim> normal   = get_slot_vector<dim>(*normals, s);
              Tensor<1, dim>       velocity = get_slot_vector<dim>(v, s);
              const double         approach = (velocity - reference) * normal;
              velocity -=
                approach * normal + (mu * approach) * slip_directions[s];
              set_slot_vector<dim>(velocity, v, s);
            }

        // Three or more deformable fields: restore the node's momentum by a
        // common shift (GrainContact::project_node does the same).
        if (!simplified && rigid_slot < 0 && n_deformable > 2)
          {
            Tensor<1, dim> momentum_after;
            for (unsigned int s = begin; s < end; ++s)
              momentum_after +=
                masses->local_element(s) * get_slot_vector<dim>(v, s);
            const Tensor<1, dim> shift =
              (momentum_after - momentum_before) / total_mass;
            for (unsigned int s = begin; s < end; ++s)
              if (masses->local_element(s) > 0.)
                set_slot_vector<dim>(get_slot_vector<dim>(v, s) - shift, v, s);
          }
      }
    return n_active;
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::project(const VectorType           &velocities,
                              VectorType                 &projected,
                              std::vector<unsigned char> *node_in_contact) const
  {
    copy_slot_vector(velocities, projected);
    return apply_projection(projected,
                            ReferenceMode::from_vector,
                            node_in_contact);
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::apply_projection(
    VectorType                 &v,
    const ReferenceMode         mode,
    std::vector<unsigned char> *node_in_contact) const
  {
    // v -> (1 - theta) v^n + theta v, project, and back. The map is affine;
    // differences of velocities (ReferenceMode::zero) see its linear part,
    // which is the projection itself. With every slot free it is the
    // identity.
    if (!any_constraint_active)
      return 0;
    const bool         affine = (mode != ReferenceMode::zero);
    const unsigned int n      = v.locally_owned_size();
    if (affine)
      for (unsigned int k = 0; k < n; ++k)
        v.local_element(k) = (1. - theta) * old_velocities->local_element(k) +
                             theta * v.local_element(k);
    const unsigned int n_active =
      apply_frozen_contact(v, mode, node_in_contact);
    for (unsigned int w = 0; w < wall_slots.size(); ++w)
      {
        Tensor<1, dim> velocity = get_slot_vector<dim>(v, wall_slots[w]);
        apply_wall_entry(w, velocity);
        set_slot_vector<dim>(velocity, v, wall_slots[w]);
      }
    if (affine)
      for (unsigned int k = 0; k < n; ++k)
        v.local_element(k) = (v.local_element(k) -
                              (1. - theta) * old_velocities->local_element(k)) /
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
  inline void
  ThetaResidual<dim>::compute_particle(const std::size_t      p,
                                       const VectorType      &theta_v,
                                       SymmetricTensor<2, 3> &new_stress,
                                       double                &plastic_strain,
                                       Tensor<2, dim>        &increment) const
  {
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    const unsigned int offset = p * per_particle;
    increment                 = 0.;
    for (unsigned int v = 0; v < per_particle; ++v)
      {
        const unsigned int    slot     = cache->slots[offset + v];
        const Tensor<1, dim> &gradient = cache->shape_gradients[offset + v];
        for (unsigned int i = 0; i < dim; ++i)
          {
            const double velocity = theta_v.local_element(slot * dim + i);
            for (unsigned int j = 0; j < dim; ++j)
              increment[i][j] += velocity * gradient[j];
          }
      }
    increment *= dt;
    plastic_strain = particle_plastic_strains[p];
    new_stress     = particle_models[p]->update_stress(particle_stresses[p],
                                                   increment,
                                                   plastic_strain);
  }



  template <int dim>
  void
  ThetaResidual<dim>::particle_update(const std::size_t      p,
                                      const VectorType      &theta_v,
                                      SymmetricTensor<2, 3> &new_stress,
                                      double                &new_plastic_strain,
                                      Tensor<2, dim>        &increment) const
  {
    compute_particle(p, theta_v, new_stress, new_plastic_strain, increment);
  }



  template <int dim>
  void
  ThetaResidual<dim>::evaluate(const VectorType &velocities,
                               VectorType       &residual,
                               const bool        simplified,
                               const bool        raw) const
  {
    constexpr unsigned int per_particle =
      TransferCache<dim>::nodes_per_particle;
    ++evaluation_count;

    // v^theta from the projected trial velocities.
    work_projected = velocities;
    const bool constrained =
      apply_projection(work_projected,
                       simplified ? ReferenceMode::frozen :
                                    ReferenceMode::from_vector,
                       nullptr) > 0 ||
      !wall_slots.empty();
    theta_velocities(work_projected, work_theta);
    work_theta.update_ghost_values();

    // Internal forces from the time-centred stress and volume (eqs. 12-13),
    // on raw pointers and local copies of theta and dt: stores into the
    // forces could otherwise alias them, and they would be reloaded for
    // every particle.
    work_forces                              = 0.;
    bool                        inverted     = false;
    const double                theta_local  = theta;
    const double                dt_local     = dt;
    const double *const         theta_values = work_theta.begin();
    double *const               forces       = work_forces.begin();
    const unsigned int *const   slots        = cache->slots.data();
    const Tensor<1, dim> *const gradients    = cache->shape_gradients.data();
    const std::size_t           n_particles  = particle_models.size();
    for (std::size_t p = 0; p < n_particles; ++p)
      {
        const ConstitutiveModel<dim> *const model = particle_models[p];
        if (model == nullptr)
          continue;
        const unsigned int offset = p * per_particle;

        // dt grad v^theta.
        Tensor<2, dim> increment;
        for (unsigned int v = 0; v < per_particle; ++v)
          {
            const unsigned int    slot     = slots[offset + v];
            const Tensor<1, dim> &gradient = gradients[offset + v];
            for (unsigned int i = 0; i < dim; ++i)
              {
                const double velocity = theta_values[slot * dim + i];
                for (unsigned int j = 0; j < dim; ++j)
                  increment[i][j] += velocity * gradient[j];
              }
          }
        increment *= dt_local;
        double plastic_strain                   = particle_plastic_strains[p];
        const SymmetricTensor<2, 3> &old_stress = particle_stresses[p];
        const SymmetricTensor<2, 3>  new_stress =
          model->update_stress(old_stress, increment, plastic_strain);

        // V^theta sigma^theta in the plane. A trial that inverts a particle
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
          particle_volumes[p] * ((1. - theta_local) + theta_local * jacobian);
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
        for (unsigned int v = 0; v < per_particle; ++v)
          {
            const unsigned int    slot     = slots[offset + v];
            const Tensor<1, dim> &gradient = gradients[offset + v];
            for (unsigned int i = 0; i < dim; ++i)
              {
                double divergence = 0.;
                for (unsigned int j = 0; j < dim; ++j)
                  divergence += stress[i][j] * gradient[j];
                forces[slot * dim + i] -= divergence;
              }
          }
      }

    work_forces.compress(VectorOperation::add);
    work_theta.zero_out_ghost_values();
    if (inverted)
      {
        // NaN on this rank makes every rank's norm NaN.
        residual = std::numeric_limits<double>::quiet_NaN();
        return;
      }

    // R = V - v^n - dt (f / m + g), in velocity units.
    const unsigned int n_slots = layout->n_slots();
    for (unsigned int s = 0; s < n_slots; ++s)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const unsigned int k = s * dim + d;
          if (slot_rigid[s])
            residual.local_element(k) =
              velocities.local_element(k) - rigid_velocities->local_element(k);
          else if (!slot_active[s])
            // Too light to carry a force: it falls with gravity.
            residual.local_element(k) = velocities.local_element(k) -
                                        old_velocities->local_element(k) -
                                        dt * gravity[d];
          else
            residual.local_element(k) =
              velocities.local_element(k) - old_velocities->local_element(k) -
              dt * (work_forces.local_element(k) / masses->local_element(s) +
                    gravity[d]);
        }
    if (raw || !constrained)
      return;

    // Constrained form R = P R_raw + (V - P V): the frozen projection P is
    // the mass-orthogonal projection onto the velocities that satisfy the
    // active contacts and walls (with friction, its sliding variant), so
    // the reactions take the component of R_raw that P removes and the
    // converged V satisfies the constraints itself. Then theta = 1/2
    // conserves energy through persistent contact (reference/physics.md
    // section 4.6), which R_raw with P V only in the stress does not.
    work_forces = residual;
    apply_projection(work_forces,
                     simplified ? ReferenceMode::zero :
                                  ReferenceMode::from_vector,
                     nullptr);
    const unsigned int n = residual.locally_owned_size();
    for (unsigned int k = 0; k < n; ++k)
      residual.local_element(k) = work_forces.local_element(k) +
                                  velocities.local_element(k) -
                                  work_projected.local_element(k);
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::colour(const unsigned int dof) const
  {
    const unsigned int    slot     = dof / dim;
    const Point<dim>      position = grid.node_position(layout->node(slot));
    const Point<dim>     &lower    = grid.lower_corner();
    const Tensor<1, dim> &h        = grid.cell_size();
    unsigned int          c        = 0;
    unsigned int          factor   = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const long index = std::lround((position[d] - lower[d]) / h[d]);
        c += factor * static_cast<unsigned int>(index % 3);
        factor *= 3;
      }
    return c + factor * (dof % dim);
  }



  template <int dim>
  double
  ThetaResidual<dim>::old_strain_energy() const
  {
    double energy = 0.;
    for (std::size_t p = 0; p < particle_models.size(); ++p)
      if (particle_models[p] != nullptr)
        energy +=
          particle_volumes[p] *
          particle_models[p]->strain_energy_density(particle_stresses[p]);
    return energy;
  }



  template <int dim>
  void
  ThetaResidual<dim>::probe_diagonal(const VectorType   &velocities,
                                     const VectorType   &residual,
                                     VectorType         &diagonal,
                                     const StepFunction &step) const
  {
    diagonal.reinit(residual, true);
    diagonal = 1.;
    VectorType direction, perturbed, probed;
    direction.reinit(residual, true);
    perturbed.reinit(residual, true);
    probed.reinit(residual, true);
    std::vector<unsigned int> dof_colours(residual.locally_owned_size());
    for (unsigned int k = 0; k < dof_colours.size(); ++k)
      dof_colours[k] = colour(k);
    for (unsigned int c = 0; c < n_colours; ++c)
      {
        direction = 0.;
        bool any  = false;
        for (unsigned int k = 0; k < dof_colours.size(); ++k)
          if (dof_colours[k] == c && slot_active[k / dim] &&
              !slot_rigid[k / dim])
            {
              direction.local_element(k) = 1.;
              any                        = true;
            }
        if (Utilities::MPI::max(any ? 1U : 0U, communicator()) == 0)
          continue;
        const double eps = step(velocities, direction);
        perturbed        = velocities;
        perturbed.add(eps, direction);
        evaluate(perturbed, probed, true);
        for (unsigned int k = 0; k < dof_colours.size(); ++k)
          if (direction.local_element(k) != 0.)
            diagonal.local_element(k) =
              (probed.local_element(k) - residual.local_element(k)) / eps;
      }
  }



  template class ThetaResidual<2>;
  template class ThetaResidual<3>;
} // namespace grainmpm
