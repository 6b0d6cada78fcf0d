// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_contact_status_h
#define grainmpm_contact_contact_status_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/constraint_impulses.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <vector>

namespace grainmpm
{
  template <int dim>
  class GrainContact;



  /**
   * The contact and wall status of one step (the active set of the
   * implicit scheme): per slot at a contact node and per (slot, closed
   * face) at the boundary, the state of the constraint, its slip direction
   * and, at contact nodes, the partner velocity v_ref. The approach the
   * gap allows enters only the decisions: freeze() decides it with the contact
   * law of GrainContact (ContactLaw::project_node(), then the walls); apply()
   * applies it with the states frozen (ContactLaw::project_node_frozen(), then
   * the walls). Given the status, the constraints are an affine map of the
   * velocities they act on; the variants of apply() give the simplified map of
   * the preconditioners and the linear parts of both maps.
   */
  template <int dim>
  class ContactStatus
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * Size the status for @p layout: every slot free, one wall entry per
     * (deformable slot, closed face of @p contact's grid) at boundary
     * nodes.
     */
    void
    reinit(const GrainContact<dim>     &contact,
           const GrainFieldLayout<dim> &layout);

    /**
     * Decide and freeze the contact and wall states for the velocities
     * @p velocities: the contact law as GrainContact::apply_contact()
     * applies it (slots with a mass not above @p mass_threshold free), then
     * the walls on the velocities after contact. With @p band > 0 and a
     * status frozen before in this step, the decisions have the
     * hysteresis of ContactLaw::classify() against the states frozen
     * before: a state changes only when the velocities cross its threshold
     * by more than @p band. Decisions after the first in a step are
     * settled (settle()): an entry that has changed often, or every entry
     * without @p catches, may only be released or stick, so that repeated
     * decisions end.
     */
    void
    freeze(const GrainContact<dim>     &contact,
           const GrainFieldLayout<dim> &layout,
           const VectorType            &masses,
           const VectorType            &normals,
           const VectorType            &velocities,
           const double                 mass_threshold,
           const double                 band    = 0.,
           const bool                   catches = true);

    /**
     * Apply the frozen status to @p velocities in place: contact at the
     * nodes with a constrained slot, v_ref from the velocities (with the
     * momentum-restoring shift at nodes of three or more deformable
     * fields), then the walls. Flags the nodes where contact is active in
     * @p node_in_contact (if given) and returns their number. With
     * @p impulses, records the impulses of contact and walls. With
     * #keep_allowed_approach constrained slots keep the approach the gap
     * allows them.
     */
    unsigned int
    apply(const GrainContact<dim>     &contact,
          const GrainFieldLayout<dim> &layout,
          const VectorType            &masses,
          const VectorType            &normals,
          VectorType                  &velocities,
          std::vector<unsigned char>  *node_in_contact = nullptr,
          ConstraintImpulses<dim>     *impulses        = nullptr) const;

    /**
     * apply() with v_ref the value frozen with the status (no shift): the
     * map of the simplified Jacobian. Returns the number of nodes where
     * contact is active.
     */
    unsigned int
    apply_simplified(const GrainContact<dim>     &contact,
                     const GrainFieldLayout<dim> &layout,
                     const VectorType            &masses,
                     const VectorType            &normals,
                     VectorType                  &velocities) const;

    /**
     * The linear part of apply_simplified(), which acts on differences of
     * velocities: v_ref zero.
     */
    void
    apply_simplified_linear_part(const GrainContact<dim>     &contact,
                                 const GrainFieldLayout<dim> &layout,
                                 const VectorType            &masses,
                                 const VectorType            &normals,
                                 VectorType &differences) const;

    /**
     * The linear part of apply() that the assembled preconditioner needs:
     * v_ref from the velocities with the shift, as apply() takes it, but
     * without the friction of sliding slots and walls (the tangential
     * correction that follows the normal one). This is the symmetric part of
     * the linearised frozen projection, which couples the fields of a node.
     */
    void
    apply_symmetric_linear_part(const GrainContact<dim>     &contact,
                                const GrainFieldLayout<dim> &layout,
                                const VectorType            &masses,
                                const VectorType            &normals,
                                VectorType                  &velocities) const;

    /**
     * Whether caught slots keep the approach the gap allows
     * (ContactLawOptions::keep_allowed_approach): the implicit contact
     * inequality. Set before freeze().
     */
    bool keep_allowed_approach = false;

    /**
     * State, slip direction, partner velocity v_ref and the approach kept
     * (zero unless #keep_allowed_approach) per owned slot.
     */
    std::vector<ContactState>   slot_state;
    std::vector<Tensor<1, dim>> slip_directions;
    std::vector<Tensor<1, dim>> references;
    std::vector<double>         slot_kept;

    /** Wall entries: (slot, face) of deformable slots at closed faces. */
    std::vector<unsigned int>   wall_slots;
    std::vector<unsigned char>  wall_faces;
    std::vector<ContactState>   wall_state;
    std::vector<Tensor<1, dim>> wall_slip_directions;
    std::vector<double>         wall_kept;

    /** Whether any slot or wall entry is not free. */
    bool any_active = false;
    /** Whether the states were decided (by freeze()) since reinit(). */
    bool decided = false;

  private:
    /**
     * Changes an entry may make in a step before it is settled (settle()):
     * catches and releases, and changes between sticking and sliding
     * (turns of the slip direction included). Long steps need more than
     * one catch and release: the first iterates of a step, far from its
     * solution, catch and release a slot several times before it comes to
     * rest, and a slot settled free early passes into its partner. With
     * each entry settled after two changes, a jammed stack at 170 times
     * the explicit step stored 3 % less elastic energy than the explicit
     * run; after four, as after six, it is within 0.5 %. Six cost two more
     * Newton iterations wherever a few slots at the edge of a contact cycled
     * between caught and released to the end, as in most steps of a
     * jammed packing. Friction settles after two changes, which do not let
     * grains pass into each other.
     */
    static constexpr unsigned char max_contact_changes = 4;
    static constexpr unsigned char max_slip_changes    = 2;

    /** The changes of one entry in this step. */
    struct Changes
    {
      unsigned char contact = 0;
      unsigned char slip    = 0;
    };

    /** Changes per slot and wall entry in this step. */
    std::vector<Changes> slot_changes;
    std::vector<Changes> wall_changes;

    /**
     * Settle the decision @p state (with slip direction @p direction) of an
     * entry that was @p before (with @p before_direction) and has made
     * @p changes in this step: a slip direction within 30 degrees of the
     * one before is not a change. With @p only_relax, or after
     * max_contact_changes catches and releases, a free entry stays free;
     * with @p only_relax, or after max_slip_changes changes of friction, a
     * sticking one does not slip and a sliding one whose slip turns sticks.
     * Counts the change in @p changes. Returns whether the state before was
     * restored.
     */
    static bool
    settle(const ContactState    before,
           const Tensor<1, dim> &before_direction,
           const bool            only_relax,
           ContactState         &state,
           Tensor<1, dim>       &direction,
           Changes              &changes);

    /**
     * Which map apply_map() applies: the affine one or its linear part
     * (v_ref zero where it is frozen, no kept approach), v_ref frozen or
     * from the velocities, with or without friction.
     */
    struct Map
    {
      bool affine;
      bool frozen_reference;
      bool friction;
    };

    /** The frozen status applied as @p map says (see apply()). */
    unsigned int
    apply_map(const Map                   &map,
              const GrainContact<dim>     &contact,
              const GrainFieldLayout<dim> &layout,
              const VectorType            &masses,
              const VectorType            &normals,
              VectorType                  &velocities,
              std::vector<unsigned char>  *node_in_contact,
              ConstraintImpulses<dim>     *impulses) const;
  };
} // namespace grainmpm

#endif
