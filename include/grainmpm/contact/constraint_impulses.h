// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_constraint_impulses_h
#define grainmpm_contact_constraint_impulses_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <array>
#include <utility>
#include <vector>

namespace grainmpm
{
  /**
   * The impulses that the constraints of one step gave the deformable
   * grains, recorded by GrainContact::apply_contact(), apply_walls() and
   * ContactStatus::apply() when they are given one, at the nodes this rank
   * owns: per box face, and per contact node and pair of grains. The
   * impulse on a slot is its mass times the change the constraint made to
   * its velocity, times #scale.
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

    /**
     * Add the impulse of box face @p face on a slot of mass @p mass whose
     * velocity it changed from @p before to @p after.
     */
    void
    add_wall(const unsigned int    face,
             const double          mass,
             const Tensor<1, dim> &before,
             const Tensor<1, dim> &after)
    {
      walls[face] += scale * mass * (after - before);
    }

    /**
     * Add the contact impulses at the node @p node of @p layout (at
     * @p position) whose fields @p fields (the velocities after the
     * constraints) had the velocities @p before, one entry per pair of
     * grains: a deformable grain against the node's rigid grain if it has
     * one, else each pair of deformable grains, whose impulse is shared by
     * the partners' masses when three or more meet.
     */
    void
    add_node(const GrainFieldLayout<dim> &layout,
             const unsigned int           node,
             const Point<dim>            &position,
             const ContactNode<dim>      &fields,
             const Tensor<1, dim>        *before);
  };



  /**
   * The work of the constraints that changed @p before into @p after
   * (dim per slot of @p layout) on the velocities @p rate, done on the
   * deformable slots (@p field_is_rigid per field): returns {friction
   * work, boundary work}. The boundary work is what rigid partners put in
   * (the reaction on the deformable slots of a node times the rigid slot's
   * velocity; walls are at rest), the friction work what the constraints
   * take out beyond it.
   */
  template <int dim>
  std::pair<double, double>
  constraint_work(const GrainFieldLayout<dim> &layout,
                  const std::vector<bool>     &field_is_rigid,
                  const LinearAlgebra::distributed::Vector<double> &masses,
                  const LinearAlgebra::distributed::Vector<double> &before,
                  const LinearAlgebra::distributed::Vector<double> &after,
                  const LinearAlgebra::distributed::Vector<double> &rate);



  /**
   * The energy the normal reactions of the constraints that changed
   * @p before into @p after take out on the velocities @p rate: at each
   * node, minus the sum over the deformable slots of the normal impulse
   * times the normal velocity relative to the node's reference (the rigid
   * slot's velocity, else the mass-weighted mean of the deformable slots,
   * else rest: a wall), along the slot's unit normal in @p normals.
   * Positive where the reactions stop an approach, as when a step catches
   * a whole impact at once.
   */
  template <int dim>
  double
  normal_constraint_dissipation(
    const GrainFieldLayout<dim>                      &layout,
    const std::vector<bool>                          &field_is_rigid,
    const LinearAlgebra::distributed::Vector<double> &masses,
    const LinearAlgebra::distributed::Vector<double> &normals,
    const LinearAlgebra::distributed::Vector<double> &before,
    const LinearAlgebra::distributed::Vector<double> &after,
    const LinearAlgebra::distributed::Vector<double> &rate);
} // namespace grainmpm

#endif
