// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <type_traits>

namespace grainmpm
{
  namespace
  {
    /**
     * The deformation gradient of the particle with @p properties after
     * the increment @p increment (dt grad v): (I + dt grad v) F.
     */
    template <int dim>
    Tensor<2, dim>
    updated_deformation_gradient(const ArrayView<double> &properties,
                                 const Tensor<2, dim>    &increment)
    {
      using Layout           = MaterialPointLayout<dim>;
      const Tensor<2, dim> F = Layout::get_deformation_gradient(properties);
      return F + increment * F;
    }



    /**
     * Store the new @p stress, @p plastic_strain, deformation gradient
     * @p F and volume @p volume (det(F) V_0) of the particle with
     * @p properties.
     */
    template <int dim>
    void
    store_particle_state(const ArrayView<double>     &properties,
                         const SymmetricTensor<2, 3> &stress,
                         const double                 plastic_strain,
                         const Tensor<2, dim>        &F,
                         const double                 volume)
    {
      using Layout = MaterialPointLayout<dim>;
      Layout::set_stress(stress, properties);
      properties[Layout::plastic_strain] = plastic_strain;
      Layout::set_deformation_gradient(F, properties);
      properties[Layout::volume] = volume;
    }



    /**
     * Add the point with @p properties at @p x to the shape sums @p sums of
     * its field (Transfer::particles_to_grid()).
     */
    template <int dim>
    void
    add_shape_sums(const ArrayView<const double> &properties,
                   const Point<dim>              &x,
                   double                        *sums)
    {
      using Layout              = MaterialPointLayout<dim>;
      const double         mass = properties[Layout::mass];
      const Tensor<1, dim> v    = Layout::get_velocity(properties);
      const Tensor<2, dim> F    = Layout::get_deformation_gradient(properties);
      const Tensor<2, dim> E =
        0.5 * (transpose(F) * F - unit_symmetric_tensor<dim>());
      sums[0] += mass;
      sums[1] += mass * E.norm();
      double *const first_moment = sums + 2;
      double *const momentum     = first_moment + dim;
      double *const angular      = momentum + dim;
      double *const second       = angular + (dim == 2 ? 1 : 3);
      for (unsigned int d = 0; d < dim; ++d)
        {
          first_moment[d] += mass * x[d];
          momentum[d] += mass * v[d];
          for (unsigned int e = 0; e < dim; ++e)
            second[d * dim + e] += mass * x[d] * x[e];
        }
      if constexpr (dim == 2)
        angular[0] += mass * (x[0] * v[1] - x[1] * v[0]);
      else
        {
          const Tensor<1, dim> x_cross_v = cross_product_3d(x, v);
          for (unsigned int d = 0; d < dim; ++d)
            angular[d] += mass * x_cross_v[d];
        }
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
    , field_keeps_shape(grains.size(), false)
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
    for (unsigned int g = 0; g < grains.size(); ++g)
      {
        const GrainShape shape = parameters.grains[g].shape;
        field_keeps_shape[g] =
          !grains[g].rigid && field_of_grain[g] == g &&
          (shape == GrainShape::disk || shape == GrainShape::sphere) &&
          !materials[grains[g].material]->has_history();
      }
    // A field shared with another grain holds no single shape.
    for (unsigned int g = 0; g < grains.size(); ++g)
      if (field_of_grain[g] != g)
        field_keeps_shape[field_of_grain[g]] = false;
  }



  template <int dim>
  void
  Transfer<dim>::reinit(const Particles::ParticleHandler<dim> &particle_handler)
  {
    cache.reinit(grid,
                 particle_handler,
                 field_of_grain,
                 parameters.material_points.shape_functions,
                 point_half_width());
    layout.reinit(cache, grid);
  }



  template <int dim>
  void
  Transfer<dim>::particles_to_grid(
    const Particles::ParticleHandler<dim> &particle_handler,
    VectorType                            *masses,
    VectorType                            &momenta,
    VectorType                            *mass_gradients,
    VectorType                            *volumes,
    std::vector<double>                   *shape_sums) const
  {
    using Layout = MaterialPointLayout<dim>;
    if (masses != nullptr)
      layout.reinit_vector(*masses, 1);
    layout.reinit_vector(momenta, dim);
    if (mass_gradients != nullptr)
      layout.reinit_vector(*mass_gradients, dim);
    if (volumes != nullptr)
      layout.reinit_vector(*volumes, 1 + dim);
    // The strain and motion of the points of a field that keeps its shape,
    // in this pass rather than one of its own (which cost 6 % of an
    // explicit run).
    double *shape_sum = nullptr;
    if (volumes != nullptr && shape_sums != nullptr &&
        parameters.contact.shape_gap)
      {
        shape_sums->assign(n_shape_sums * field_keeps_shape.size(), 0.);
        if (std::find(field_keeps_shape.begin(),
                      field_keeps_shape.end(),
                      true) != field_keeps_shape.end())
          shape_sum = shape_sums->data();
      }

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
        const unsigned char *const fill_read = layout.fill_read_flags();
        // The first moment of a particle's box (half-width l) under the
        // hat: V_p (S_ip x_p + l^2 / 3 grad S_ip), exact where the hat is
        // linear across the box.
        const Tensor<1, dim> half_width = point_half_width();
        Tensor<1, dim>       box_moment;
        for (unsigned int d = 0; d < dim; ++d)
          box_moment[d] = half_width[d] * half_width[d] / 3.;
        for_each_particle(
          particle_handler,
          [&](const std::size_t p, const auto &particle)
            __attribute__((always_inline)) {
              const auto   properties = particle->get_properties();
              const double mass       = properties[Layout::mass];
              const double volume     = properties[Layout::volume];
              [[maybe_unused]] const Point<dim> &location =
                particle->get_location();
              // Volumes only from the points that reach a slot whose fill
              // the contact law reads, to all their slots (the others are
              // not read).
              const auto scatter_entries = [&](auto with_point_volumes)
                __attribute__((always_inline))
              {
                constexpr bool add_point_volumes =
                  decltype(with_point_volumes)::value;
                cache.for_each_entry(p, [&](const unsigned int e) {
                  const unsigned int    slot     = cache.slots[e];
                  const double          shape    = cache.shape_values[e];
                  const Tensor<1, dim> &gradient = cache.shape_gradients[e];
                  if constexpr (add_masses)
                    mass_values[slot] += mass * shape;
                  if constexpr (add_point_volumes)
                    {
                      double *const sums = volume_sum + slot * (1 + dim);
                      sums[0] += volume * shape;
                      for (unsigned int d = 0; d < dim; ++d)
                        sums[1 + d] += volume * (shape * location[d] +
                                                 box_moment[d] * gradient[d]);
                    }
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      momentum[slot * dim + d] +=
                        mass * shape * properties[Layout::velocity + d];
                      if constexpr (add_gradients)
                        gradient_sum[slot * dim + d] += mass * gradient[d];
                    }
                });
              };
              if constexpr (add_volumes)
                {
                  // (A field that keeps its shape is its grain's.)
                  const unsigned int grain = Layout::get_grain(properties);
                  if (shape_sum != nullptr && field_keeps_shape[grain])
                    add_shape_sums<dim>(properties,
                                        particle->get_location(),
                                        shape_sum + n_shape_sums * grain);
                  unsigned char reads = 0;
                  cache.for_each_entry(p, [&](const unsigned int e) {
                    reads |= fill_read[cache.slots[e]];
                  });
                  if (reads != 0)
                    return scatter_entries(std::true_type());
                }
              scatter_entries(std::false_type());
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
    LedgerIncrements                &ledger,
    double                          *strain_energy) const
  {
    update_states(particle_handler,
                  velocities,
                  dt,
                  ledger,
                  strain_energy,
                  Tensor<1, dim>(),
                  nullptr);
  }



  template <int dim>
  double
  Transfer<dim>::trial_strain_energy(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    double                          &plastic_work) const
  {
    double           strain_energy = 0.;
    LedgerIncrements ledger;
    update_states(particle_handler,
                  velocities,
                  dt,
                  ledger,
                  &strain_energy,
                  Tensor<1, dim>(),
                  nullptr,
                  false);
    plastic_work += ledger.plastic_work;
    return strain_energy;
  }



  template <int dim>
  void
  Transfer<dim>::update_particle_states_and_forces(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    const Tensor<1, dim>            &gravity,
    VectorType                      &forces,
    LedgerIncrements                &ledger) const
  {
    layout.reinit_vector(forces, dim);
    update_states(
      particle_handler, velocities, dt, ledger, nullptr, gravity, &forces);
    forces.compress(VectorOperation::add);
  }



  template <int dim>
  void
  Transfer<dim>::update_states(
    Particles::ParticleHandler<dim> &particle_handler,
    const VectorType                &velocities,
    const double                     dt,
    LedgerIncrements                &ledger,
    double                          *strain_energy,
    const Tensor<1, dim>            &gravity,
    VectorType                      *forces,
    const bool                       store) const
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
        // The model updates s = J sigma (Kirchhoff) or sigma (Cauchy); the
        // point stores sigma.
        const double initial_volume = properties[Layout::initial_volume];
        const double old_volume     = properties[Layout::volume];
        const Tensor<2, dim> F =
          updated_deformation_gradient<dim>(properties, increment);
        const double                volume = determinant(F) * initial_volume;
        const SymmetricTensor<2, 3> old_rate_stress =
          model.rate_stress_factor(old_volume, initial_volume) *
          Layout::get_stress(properties);
        const SymmetricTensor<2, 3> rate_stress =
          model.update_stress(old_rate_stress, increment, plastic_strain);
        const SymmetricTensor<2, 3> stress =
          rate_stress / model.rate_stress_factor(volume, initial_volume);
        if (store)
          store_particle_state(properties, stress, plastic_strain, F, volume);
        const double energy_density = model.strain_energy_density(rate_stress);
        const double energy_volume =
          model.energy_volume(volume, initial_volume);
        if (strain_energy != nullptr)
          *strain_energy += energy_volume * energy_density;
        ledger.plastic_work +=
          energy_volume *
          model.plastic_work_density(rate_stress,
                                     plastic_strain - old_plastic_strain);
        // The energy V_e W(s) changes by the mean V_e times the change of W,
        // the elastic work of the stresses, plus the mean W times the change
        // of V_e, which is not work: zero for the Kirchhoff stress (V_e =
        // V0), the hypoelastic correction of the Cauchy stress (V_e = V).
        if (store)
          ledger.hypoelastic_correction +=
            0.5 *
            (model.strain_energy_density(old_rate_stress) + energy_density) *
            (energy_volume - model.energy_volume(old_volume, initial_volume));
        if (force_array != nullptr)
          add_force(
            p, properties[Layout::mass], volume, stress, gravity, force_array);
      });
  }



  template class Transfer<2>;
  template class Transfer<3>;
} // namespace grainmpm
