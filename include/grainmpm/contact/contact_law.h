// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_contact_law_h
#define grainmpm_contact_contact_law_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>

#include <deal.II/base/tensor.h>

namespace grainmpm
{
  /**
   * The state of one constraint (a slot at a contact node, or a slot at a
   * wall): free (receding, left alone), sliding (the normal part of the
   * velocity relative to the partner is removed and, with friction, the
   * tangential part reduced by mu times the normal part along a slip
   * direction) or sticking (the slot takes the partner's velocity).
   */
  enum class ContactState : unsigned char
  {
    free     = 0,
    sliding  = 1,
    sticking = 2
  };



  /**
   * How the contact law decides at a node: the contact model and its
   * friction coefficient, the mass below which a field is left alone, and
   * the hysteresis band of the decisions against the states decided
   * before (ContactLaw::classify()).
   */
  struct ContactLawOptions
  {
    ContactModel model                = ContactModel::frictionless;
    double       friction_coefficient = 0.;
    /** Fields with a mass not above this are left alone. */
    double mass_threshold = 0.;
    /** The hysteresis band (a velocity; with previous states only). */
    double band = 0.;
    /**
     * A caught field keeps the approach the gap allows (the implicit
     * contact inequality: the gap closes exactly within the step) instead
     * of losing its whole approach.
     */
    bool keep_allowed_approach = false;

    /** The friction coefficient of the model (0 without friction). */
    double
    friction() const
    {
      return model == ContactModel::coulomb_friction ? friction_coefficient :
                                                       0.;
    }
  };



  /**
   * The fields of one contact node for the contact law: contiguous arrays
   * of #n entries, one per field (slot) of the node. The first five
   * members are the node; the others are optional (null: not given).
   */
  template <int dim>
  struct ContactNode
  {
    /** The number of fields. */
    unsigned int n = 0;
    /** Their masses, whether they are rigid, and their unit normals. */
    const double         *masses  = nullptr;
    const bool           *rigid   = nullptr;
    const Tensor<1, dim> *normals = nullptr;
    /** Their velocities, corrected in place. */
    Tensor<1, dim> *velocities = nullptr;

    /**
     * The approach speed the gap allows each field (none: 0): a field that
     * approaches no faster is left alone. With frozen states
     * (project_node_frozen()), the approach each constrained field keeps.
     */
    const double *allowed = nullptr;
    /** ContactLaw::project_node(): the states decided, with hysteresis. */
    const ContactState *previous_states = nullptr;
    /**
     * ContactLaw::project_node() output: the states decided and their slip
     * directions (both or neither), and the partner velocity v_ref.
     */
    ContactState   *states          = nullptr;
    Tensor<1, dim> *slip_directions = nullptr;
    Tensor<1, dim> *reference       = nullptr;

    /**
     * The light-field fraction (Contact/Light field fraction): a
     * deformable field with less mass than this fraction of the heaviest
     * deformable field of the node is light. The law leaves it alone,
     * and it does not count for the partner velocity v_ref or the
     * momentum the law conserves (zero: no field is light).
     */
    double light_fraction = 0.;
  };



  /**
   * The Bardenhagen-Brackbill-Sulsky contact law at one grid node
   * (Bardenhagen, Brackbill & Sulsky 2000; Cummins & Brackbill 2001, eqs.
   * 5-6) and the unilateral walls, pointwise: the state of one constraint
   * (classify(), classify_wall()), its application (apply_state(),
   * apply_wall()), and the law at a node (project_node() deciding the
   * states, project_node_frozen() with frozen states). GrainContact sweeps
   * it over the contact nodes and walls and freezes it.
   *
   * Field g of a node approaches iff (v_g - v_ref) . n_g > 0, v_ref being
   * the centre-of-mass velocity of the node (or the velocity of a rigid
   * field, which has infinite mass); then the normal part of v_g - v_ref is
   * removed and the tangential part reduced by Coulomb friction (stick if
   * mu D >= |dv_t|, else slip by mu D). Receding fields are left alone.
   * With two deformable fields this conserves the node's momentum exactly.
   * With three or more the normals cannot all be pairwise antiparallel;
   * the projection then alternates with a common velocity shift that
   * restores the node's momentum, until the shift vanishes, so momentum is
   * conserved at every contact node. With decided states (explicit), each
   * pass decides again, so no field is left approaching; with frozen
   * states (implicit), each pass applies the same states, so every
   * constrained field satisfies its constraint. With an allowed approach
   * a_g (the gap check, GapEstimator) a field is caught only if D > a_g.
   * In the explicit scheme it then loses its whole approach, as without
   * the gap check. In the implicit scheme
   * (ContactLawOptions::keep_allowed_approach) it keeps the approach a_g:
   * the constraint is the inequality D <= a_g on the theta velocity, so
   * the gap closes exactly within the step and not before.
   */
  template <int dim>
  class ContactLaw
  {
  public:
    /**
     * The contact law at the node @p node, deciding the states: corrects
     * its velocities in place (fields with a mass not above
     * @p options.mass_threshold are left alone) and returns true if some
     * field was corrected. If @p node has states, they receive the state
     * of each field decided in the first pass (and its slip directions
     * the slip directions); if it has a reference, it receives the partner
     * velocity. With previous states and @p options.band > 0 the decisions
     * of the first pass have the hysteresis of classify().
     */
    static bool
    project_node(const ContactLawOptions &options,
                 const ContactNode<dim>  &node);

    /**
     * The contact law at the node @p node with the states @p states and
     * slip directions @p slip_directions frozen, applied once, with the
     * friction coefficient @p mu. v_ref comes from the velocities (with
     * one momentum-restoring shift at nodes of three or more deformable
     * fields) if @p fixed_reference is null, else it is
     * *@p fixed_reference (no shift).
     */
    static void
    project_node_frozen(const ContactNode<dim> &node,
                        const ContactState     *states,
                        const Tensor<1, dim>   *slip_directions,
                        const double            mu,
                        const Tensor<1, dim>   *fixed_reference = nullptr);

    /**
     * The state of a velocity @p relative to its partner (or wall) with
     * the normal @p normal (pointing into the partner) and friction
     * coefficient @p mu: with D the approach speed, free if D <= @p allowed,
     * sticking if mu D >= |v_t|, else sliding; sets the slip direction of
     * a sliding state with friction, zero otherwise. With a hysteresis
     * band @p band > 0 the tests are shifted against a change of the state
     * @p previous: a constrained slot is released only when
     * D - allowed < -band and a free one is caught only when
     * D - allowed > band; a
     * sticking slot slips only when |v_t| > mu D + band and a sliding one
     * sticks only when |v_t| < mu D - band. With @p keep the caught field
     * keeps the approach @p allowed, and D - allowed takes the place of D in
     * the friction tests.
     */
    static ContactState
    classify(const Tensor<1, dim> &relative,
             const Tensor<1, dim> &normal,
             const double          mu,
             Tensor<1, dim>       &slip_direction,
             const double          allowed  = 0.,
             const ContactState    previous = ContactState::free,
             const double          band     = 0.,
             const bool            keep     = false);

    /**
     * Apply @p state to @p velocity with partner velocity @p reference and
     * the approach @p kept that the constraint leaves: sticking takes
     * v_ref + kept n, sliding removes the approach beyond @p kept,
     * D - kept, and mu (D - kept) of the slip along the slip direction.
     */
    static void
    apply_state(const ContactState    state,
                const Tensor<1, dim> &normal,
                const double          mu,
                const Tensor<1, dim> &slip_direction,
                const Tensor<1, dim> &reference,
                Tensor<1, dim>       &velocity,
                const double          kept = 0.);

    /**
     * The state of a wall with @p condition and outward normal @p normal
     * (pointing into the wall) for @p velocity.
     */
    static ContactState
    classify_wall(const BoundaryCondition &condition,
                  const Tensor<1, dim>    &normal,
                  const Tensor<1, dim>    &velocity,
                  Tensor<1, dim>          &slip_direction,
                  const double             allowed  = 0.,
                  const ContactState       previous = ContactState::free,
                  const double             band     = 0.,
                  const bool               keep     = false);

    /**
     * The approach a wall entry with @p condition in @p state keeps when
     * the gap allows @p allowed and caught fields keep it (@p keep): none
     * at no-slip walls and for free entries.
     */
    static double
    wall_kept_approach(const BoundaryCondition &condition,
                       const ContactState       state,
                       const double             allowed,
                       const bool               keep)
    {
      return keep && state != ContactState::free &&
                 condition.type != BoundaryType::no_slip ?
               allowed :
               0.;
    }

    /**
     * The normal speed @p turning that a wall with @p condition leaves to a
     * field (GapEstimator::wall_turning_speed()): all of it at the
     * unilateral walls (free slip, friction), none at the others.
     */
    static double
    wall_turning(const BoundaryCondition &condition, const double turning)
    {
      return condition.type == BoundaryType::free_slip ||
                 condition.type == BoundaryType::friction ?
               turning :
               0.;
    }

    /**
     * The unilateral wall condition with outward wall normal @p normal
     * applied to @p velocity (classify_wall with the approach @p allowed by
     * the gap, then apply_state with the wall at rest), to the normal
     * velocity beyond the speed @p turning that the wall leaves to the
     * field (wall_turning()).
     */
    static void
    apply_wall(const BoundaryCondition &condition,
               const Tensor<1, dim>    &normal,
               Tensor<1, dim>          &velocity,
               const double             allowed = 0.,
               const double             turning = 0.);

    /** Friction coefficient of a wall with @p condition. */
    static double
    wall_friction(const BoundaryCondition &condition)
    {
      return condition.type == BoundaryType::friction ?
               condition.friction_coefficient :
               0.;
    }

    /** Outward unit normal of box face @p face (x-, x+, y-, ...). */
    static Tensor<1, dim>
    face_normal(const unsigned int face)
    {
      Tensor<1, dim> normal;
      normal[face / 2] = (face % 2 == 0) ? -1. : 1.;
      return normal;
    }

  private:
    /**
     * One pass of the deciding law over the fields of @p node with partner
     * velocity @p reference, deformable fields lighter than @p floor left
     * alone: decides each field's state (recorded in @p states and
     * @p slip_directions if given, with the hysteresis of classify()
     * against @p previous_states if given) and applies it. Returns whether
     * a field was corrected.
     */
    static bool
    decide_and_project(const ContactLawOptions &options,
                       const ContactNode<dim>  &node,
                       const double             floor,
                       const Tensor<1, dim>    &reference,
                       ContactState            *states,
                       Tensor<1, dim>          *slip_directions,
                       const ContactState      *previous_states);
  };
} // namespace grainmpm

#endif
