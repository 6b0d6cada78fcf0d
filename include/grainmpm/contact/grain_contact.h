// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_grain_contact_h
#define grainmpm_contact_grain_contact_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/contact/constraint_impulses.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/contact/contact_node_fields.h>
#include <grainmpm/contact/contact_status.h>
#include <grainmpm/contact/gap_estimator.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/rigid_grain_motion.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <utility>
#include <vector>

namespace grainmpm
{
  /**
   * The Bardenhagen-Brackbill-Sulsky contact between the velocity fields of
   * grains that meet at a grid node (Bardenhagen, Brackbill & Sulsky 2000;
   * Cummins & Brackbill 2001, eqs. 5-6), the rigid walls on the faces of
   * the box, and the rigid grains: the contact normals and the sweeps of
   * the contact law (ContactLaw) over the contact nodes and the walls,
   * deciding the states (the explicit scheme, and ContactStatus::freeze()
   * for the implicit one, which applies them frozen with ContactStatus).
   *
   * At a contact node every field g gets the normal
   * n_g = (g_g - sum_{k != g} g_k) / |...| from the mass gradients
   * g_g = sum_p m_p grad S_ip, so that two fields get exactly antiparallel
   * normals.
   *
   * With `Contact/Gap check`, a field may approach its partner by the gap
   * between their surfaces in one step (GapEstimator); @p field_keeps_shape
   * (Transfer::get_field_keeps_shape()) says which fields it may read from
   * the shapes of their grains.
   */
  template <int dim>
  class GrainContact
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * @p field_is_rigid says for each field whether it belongs to a rigid
     * grain; rigid grains move as @p rigid_motion says.
     */
    GrainContact(const ContactParameters                 &parameters,
                 const BackgroundGrid<dim>               &grid,
                 const RigidGrainMotion<dim>             &rigid_motion,
                 const std::vector<bool>                 &field_is_rigid,
                 const std::vector<bool>                 &field_keeps_shape,
                 const std::vector<GrainInfo<dim>>       &grains,
                 const std::vector<GrainParameters<dim>> &grain_parameters);

    /**
     * Contact normals (dim numbers per slot) at the contact nodes of
     * @p layout: from the shape of a rigid grain at its nodes (where
     * RigidGrainMotion::surface_normal() knows it), from the mass gradients
     * @p mass_gradients elsewhere; zero away from the contact nodes.
     */
    void
    compute_normals(const GrainFieldLayout<dim> &layout,
                    const VectorType            &mass_gradients,
                    VectorType                  &normals) const;

    /** Whether the contact law checks the gap (`Contact/Gap check`). */
    bool
    uses_gaps() const
    {
      return gaps.enabled();
    }

    /**
     * The fill fractions and centroids of the owned slots of @p layout from
     * the slot volumes and their moments @p volumes, and the shapes of the
     * grains that keep theirs at their centres of mass from @p masses, for
     * a step of length @p dt, those strained little enough according to
     * their points' sums @p shape_sums (Transfer::particles_to_grid()):
     * the data of the gap check until the next call
     * (GapEstimator::compute()). Collective.
     */
    void
    compute_gaps(const GrainFieldLayout<dim> &layout,
                 const std::vector<double>   &shape_sums,
                 const VectorType            &masses,
                 const VectorType            &volumes,
                 const double                 dt)
    {
      gaps.compute(layout, shape_sums, masses, volumes, dt);
    }

    /**
     * Set the slots of rigid fields to their velocity at @p time
     * (RigidGrainMotion::prescribe()).
     */
    void
    prescribe_rigid_velocities(const GrainFieldLayout<dim> &layout,
                               VectorType                  &velocities,
                               const double                 time) const
    {
      rigid_motion.prescribe(layout, velocities, time);
    }

    /**
     * Apply the contact law to @p velocities (dim per slot) at every
     * contact node, deciding the states (ContactLaw::project_node()). Sets
     * (*@p node_in_contact)[node] (if given) for nodes where a field was
     * corrected, and returns their number. With @p impulses, records the
     * impulses of the corrections.
     */
    unsigned int
    apply_contact(const GrainFieldLayout<dim> &layout,
                  const VectorType            &masses,
                  const VectorType            &normals,
                  VectorType                  &velocities,
                  std::vector<unsigned char>  *node_in_contact = nullptr,
                  ConstraintImpulses<dim>     *impulses        = nullptr) const;

    /**
     * The sweep of apply_contact() with the law's @p options (its mass
     * threshold and hysteresis band), recording in @p status what it
     * decides (ContactStatus::freeze()): per slot the state and slip
     * direction of the first pass, the partner velocity and the approach
     * the gap allows. With @p previous_states (per slot) the decisions have
     * the hysteresis of ContactLaw::classify() against them.
     */
    void
    decide_contact(const GrainFieldLayout<dim>     &layout,
                   const VectorType                &masses,
                   const VectorType                &normals,
                   VectorType                      &velocities,
                   const ContactLawOptions         &options,
                   const std::vector<ContactState> *previous_states,
                   ContactStatus<dim>              &status) const;

    /**
     * Apply the wall conditions of the box faces to the deformable fields
     * at boundary nodes, face after face, deciding the states; with
     * @p impulses, add what each face gave the slots of @p masses.
     */
    void
    apply_walls(const GrainFieldLayout<dim> &layout,
                VectorType                  &velocities,
                const VectorType            *masses   = nullptr,
                ConstraintImpulses<dim>     *impulses = nullptr) const;

    /**
     * The work of the constraints that changed @p before into @p after
     * on the velocities @p rate: {friction work, boundary work}
     * (constraint_work() with the rigid fields of the contact).
     */
    std::pair<double, double>
    constraint_work(const GrainFieldLayout<dim> &layout,
                    const VectorType            &masses,
                    const VectorType            &before,
                    const VectorType            &after,
                    const VectorType            &rate) const
    {
      return grainmpm::constraint_work(
        layout, field_is_rigid, masses, before, after, rate);
    }

    /**
     * The energy the normal reactions that changed @p before into @p after
     * take out on the velocities @p rate
     * (normal_constraint_dissipation() with the rigid fields of the
     * contact).
     */
    double
    normal_dissipation(const GrainFieldLayout<dim> &layout,
                       const VectorType            &masses,
                       const VectorType            &normals,
                       const VectorType            &before,
                       const VectorType            &after,
                       const VectorType            &rate) const
    {
      return normal_constraint_dissipation(
        layout, field_is_rigid, masses, normals, before, after, rate);
    }

    /**
     * The options of the contact law: the contact model and friction
     * coefficient of the parameters, with @p mass_threshold and the
     * hysteresis band @p band.
     */
    ContactLawOptions
    law_options(const double mass_threshold = 0., const double band = 0.) const
    {
      ContactLawOptions options;
      options.model                = parameters.model;
      options.friction_coefficient = parameters.friction_coefficient;
      options.mass_threshold       = mass_threshold;
      options.band                 = band;
      return options;
    }

    /** Contact/Light field fraction (ContactNode::light_fraction). */
    double
    light_field_fraction() const
    {
      return parameters.light_field_fraction;
    }

    /** The grid, whose box faces are the walls. */
    const BackgroundGrid<dim> &
    get_grid() const
    {
      return grid;
    }

    /** For each field: whether it belongs to a rigid grain. */
    const std::vector<bool> &
    get_field_is_rigid() const
    {
      return field_is_rigid;
    }

    /** The gap check. */
    const GapEstimator<dim> &
    get_gaps() const
    {
      return gaps;
    }

  private:
    /**
     * The sweep of apply_contact() and decide_contact(): the law with
     * @p options at every contact node, recording what the arguments that
     * are not null ask for.
     */
    unsigned int
    sweep(const GrainFieldLayout<dim>     &layout,
          const VectorType                &masses,
          const VectorType                &normals,
          VectorType                      &velocities,
          const ContactLawOptions         &options,
          const std::vector<ContactState> *previous_states,
          ContactStatus<dim>              *status,
          std::vector<unsigned char>      *node_in_contact,
          ConstraintImpulses<dim>         *impulses) const;

    const ContactParameters     &parameters;
    const BackgroundGrid<dim>   &grid;
    const RigidGrainMotion<dim> &rigid_motion;
    const std::vector<bool>     &field_is_rigid;

    /** The gap check. */
    GapEstimator<dim> gaps;
  };
} // namespace grainmpm

#endif
