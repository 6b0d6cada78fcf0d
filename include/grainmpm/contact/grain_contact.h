// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_grain_contact_h
#define grainmpm_contact_grain_contact_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/contact/contact_node_fields.h>
#include <grainmpm/contact/gap_estimator.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <array>
#include <vector>

namespace grainmpm
{
  /**
   * The contact and wall status of one step, frozen by GrainContact::freeze
   * and applied by GrainContact::apply_frozen (the implicit scheme). Given
   * the status, the constraints are a linear map of the velocities.
   */
  template <int dim>
  struct ContactStatus
  {
    /** State, slip direction and partner velocity v_ref per owned slot. */
    std::vector<ContactState>   slot_state;
    std::vector<Tensor<1, dim>> slip_directions;
    std::vector<Tensor<1, dim>> references;
    /** The approach speed the gap allows per owned slot (gap check). */
    std::vector<double> allowed;

    /** Wall entries: (slot, face) of deformable slots at closed faces. */
    std::vector<unsigned int>   wall_slots;
    std::vector<unsigned char>  wall_faces;
    std::vector<ContactState>   wall_state;
    std::vector<Tensor<1, dim>> wall_slip_directions;
    std::vector<double>         wall_allowed;

    /** Whether any slot or wall entry is not free. */
    bool any_active = false;
    /** Whether the states were decided (by freeze) since reinit_status. */
    bool decided = false;
  };



  /**
   * The impulses that the constraints of one step gave the deformable
   * grains, recorded by GrainContact::apply_contact(), apply_walls() and
   * apply_frozen() when they are given one, at the nodes this rank owns:
   * per box face, and per contact node and pair of grains. The impulse on
   * a slot is its mass times the change the constraint made to its
   * velocity, times #scale.
   */
  template <int dim>
  struct ConstraintImpulses
  {
    /** One pair of grains at one contact node. */
    struct Pair
    {
      /** The two grains, grain_a < grain_b. */
      unsigned int grain_a = 0;
      unsigned int grain_b = 0;
      /** The impulse on grain_b from grain_a. */
      Tensor<1, dim> impulse;
      /** The unit contact normal at the node, out of grain_a. */
      Tensor<1, dim> normal;
      /** Where: the node. */
      Point<dim> position;
    };

    /**
     * From velocity changes to impulses on the end velocity: 1, or
     * 1 / theta where the constraints act on v^theta.
     */
    double scale = 1.;
    /** The impulse each box face (x-, x+, y-, ...) gave the grains. */
    std::array<Tensor<1, dim>, 2 * dim> walls;
    /** Contact between grains, rigid grains included. */
    std::vector<Pair> pairs;

    /** Forget everything recorded (#scale stays). */
    void
    clear()
    {
      walls.fill(Tensor<1, dim>());
      pairs.clear();
    }
  };



  /**
   * The Bardenhagen-Brackbill-Sulsky contact between the velocity fields of
   * grains that meet at a grid node (Bardenhagen, Brackbill & Sulsky 2000;
   * Cummins & Brackbill 2001, eqs. 5-6), the rigid walls on the faces of
   * the box, and the rigid grains: the contact normals and the sweeps of
   * the contact law (ContactLaw) over the contact nodes and the walls. The
   * explicit scheme applies the law as it decides the states, the implicit
   * residual applies it with the states frozen.
   *
   * At a contact node every field g gets the normal
   * n_g = (g_g - sum_{k != g} g_k) / |...| from the mass gradients
   * g_g = sum_p m_p grad S_ip, so that two fields get exactly antiparallel
   * normals.
   *
   * With `Contact/Gap check`, a field may approach its partner by the gap
   * between their surfaces in one step (GapEstimator).
   */
  template <int dim>
  class GrainContact
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * Where the projection takes the partner velocity v_ref of a node: from
     * the velocities it acts on (the rigid field or the centre of mass,
     * with the momentum-restoring shift at nodes of three or more
     * deformable fields), the value frozen with the status (no shift: the
     * preconditioner's simplified Jacobian), or zero (no shift: the linear
     * part of the simplified projection, which acts on velocity
     * differences). `linear` takes it from the velocities as
     * `from_velocities` does, shift included, but leaves out the approach
     * the gap allows and the friction of sliding fields and walls (the
     * tangential correction that follows the normal one): the symmetric
     * part of the linearised frozen projection, which couples the fields
     * of a node, for the assembled preconditioner.
     */
    enum class Reference
    {
      from_velocities,
      frozen,
      zero,
      linear
    };

    /**
     * @p field_is_rigid says for each field whether it belongs to a rigid
     * grain; rigid grains take their prescribed velocities from @p grains.
     */
    GrainContact(const ContactParameters           &parameters,
                 const BackgroundGrid<dim>         &grid,
                 const std::vector<GrainInfo<dim>> &grains,
                 const std::vector<bool>           &field_is_rigid);

    /**
     * Contact normals (dim numbers per slot) at the contact nodes of
     * @p layout from the mass gradients @p mass_gradients; zero elsewhere.
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
     * The fill fractions of the owned slots of @p layout from the slot
     * volumes @p volumes, for a step of length @p dt: the data of the gap
     * check until the next call (GapEstimator::compute()).
     */
    void
    compute_gaps(const GrainFieldLayout<dim> &layout,
                 const VectorType            &volumes,
                 const double                 dt)
    {
      gaps.compute(layout, volumes, dt);
    }

    /** Set the slots of rigid fields to their velocity at @p time. */
    void
    prescribe_rigid_velocities(const GrainFieldLayout<dim> &layout,
                               VectorType                  &velocities,
                               const double                 time) const;

    /**
     * Apply the contact law to @p velocities (dim per slot) at every
     * contact node, deciding the states. Slots with a mass not above
     * @p mass_threshold are left alone. Sets (*@p node_in_contact)[node]
     * (if given) for nodes where a field was corrected, and returns their
     * number. If
     * @p status is given, records the states decided (a field corrected in
     * any pass keeps the state of its last correction) and the partner
     * velocities; if @p impulses is given, the impulses of the corrections.
     * With @p previous_states (per slot) and @p band > 0 the decisions have
     * the hysteresis of classify() against those states (freeze()).
     */
    unsigned int
    apply_contact(const GrainFieldLayout<dim>     &layout,
                  const VectorType                &masses,
                  const VectorType                &normals,
                  VectorType                      &velocities,
                  std::vector<unsigned char>      *node_in_contact,
                  const double                     mass_threshold  = 0.,
                  ContactStatus<dim>              *status          = nullptr,
                  ConstraintImpulses<dim>         *impulses        = nullptr,
                  const std::vector<ContactState> *previous_states = nullptr,
                  const double                     band            = 0.) const;

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
     * Size @p status for @p layout: every slot free, one wall entry per
     * (deformable slot, closed face) at boundary nodes.
     */
    void
    reinit_status(const GrainFieldLayout<dim> &layout,
                  ContactStatus<dim>          &status) const;

    /**
     * Decide and freeze the contact and wall states for the velocities
     * @p velocities: the contact law as apply_contact() applies it (slots
     * with a mass not above @p mass_threshold free), then the walls on the
     * velocities after contact. With @p band > 0 and a status frozen
     * before in this step, the decisions have the hysteresis of
     * classify() against the states in @p status: a state changes only
     * when the velocities cross its threshold by more than @p band.
     */
    void
    freeze(const GrainFieldLayout<dim> &layout,
           const VectorType            &masses,
           const VectorType            &normals,
           const VectorType            &velocities,
           const double                 mass_threshold,
           ContactStatus<dim>          &status,
           const double                 band = 0.) const;

    /**
     * Apply the frozen @p status to @p velocities in place: contact at the
     * nodes with a constrained slot, with v_ref taken as @p reference
     * says, then the walls. Flags the nodes where contact is active in
     * @p node_in_contact (if given) and returns their number. With
     * @p impulses, records the impulses of contact and walls.
     */
    unsigned int
    apply_frozen(const GrainFieldLayout<dim> &layout,
                 const VectorType            &masses,
                 const VectorType            &normals,
                 const ContactStatus<dim>    &status,
                 const Reference              reference,
                 VectorType                  &velocities,
                 std::vector<unsigned char>  *node_in_contact = nullptr,
                 ConstraintImpulses<dim>     *impulses        = nullptr) const;

    /**
     * The work of the constraints that changed @p before into @p after
     * (dim per slot) on the velocities @p rate, done on the deformable
     * slots: returns {friction work, boundary work}. The boundary work is
     * what rigid partners put in (the reaction on the deformable slots of
     * a node times the rigid slot's velocity; walls are at rest), the
     * friction work what the constraints take out beyond it.
     */
    std::pair<double, double>
    constraint_work(const GrainFieldLayout<dim> &layout,
                    const VectorType            &masses,
                    const VectorType            &before,
                    const VectorType            &after,
                    const VectorType            &rate) const;

  private:
    /**
     * Add the contact impulses of the fields @p fields_begin.. of @p node
     * (@p n of them, with @p masses and @p normals, rigid as @p rigid)
     * that changed @p before into @p after to @p impulses, one entry per
     * pair of grains: a deformable grain against the node's rigid grain
     * if it has one, else each pair of deformable grains, whose impulse is
     * shared by the partners' masses when three or more meet.
     */
    void
    record_impulses(const GrainFieldLayout<dim> &layout,
                    const unsigned int           node,
                    const unsigned int           n,
                    const double                *masses,
                    const bool                  *rigid,
                    const Tensor<1, dim>        *normals,
                    const Tensor<1, dim>        *before,
                    const Tensor<1, dim>        *after,
                    ConstraintImpulses<dim>     &impulses) const;

    /** The friction coefficient of the contact model (0 without). */
    double
    friction_coefficient() const
    {
      return parameters.model == ContactModel::coulomb_friction ?
               parameters.friction_coefficient :
               0.;
    }

    const ContactParameters           &parameters;
    const BackgroundGrid<dim>         &grid;
    const std::vector<GrainInfo<dim>> &grains;
    const std::vector<bool>           &field_is_rigid;
    const bool                         has_rigid_fields;

    /** The gap check. */
    GapEstimator<dim> gaps;
  };
} // namespace grainmpm

#endif
