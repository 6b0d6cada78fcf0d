// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_gap_estimator_h
#define grainmpm_contact_gap_estimator_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/particles/grain_parameters.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/rigid_grain_motion.h>
#include <grainmpm/transfer/shape_functions.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace grainmpm
{
  /**
   * The gap check of the contact law (`Contact/Gap check`): the approach
   * speed the gap between two surfaces allows a field in one step.
   *
   * Field g may approach its partner by the gap between their surfaces in
   * one step: the contact law compares the approach D (relative to the
   * node's centre-of-mass velocity) with the allowed approach speed
   * a_g = (m_rest / m) gap / dt (a_g = gap / dt with a rigid partner or a
   * wall; m_rest the mass of the node's other deformable fields, m of all)
   * and catches the field only if D > a_g (ContactLaw::classify()); a
   * caught field then loses its whole approach. With two fields the shares
   * m_rest / m make both decisions the same test, relative approach >
   * gap / dt. The gap comes from the fill fractions
   * phi_g = sum_p V_p S_ip / V_i of the node's support V_i (cut at the box
   * faces): a flat surface filling phi of the support lies at
   * s = Phi^{-1}(phi) cells along the normal (Phi the integral of the hat,
   * HatKernel), so gap = h_n (Phi^{-1}(1 - phi_rest) - Phi^{-1}(phi_g)),
   * h_n the cell size along the normal. Two flat blocks in contact have
   * phi_a + phi_b = 1, gap 0. A wall gives the smaller of
   * h (1 - sqrt(phi_g)) and h (3 c - 1) / 2, c the centroid of the field's
   * volume under the node's hat along the wall's normal in cells
   * (c = 1/3 for material that reaches the wall): where a grain's corner
   * covers only a part of the node's support along the wall, the filled
   * fraction puts the surface away from the wall, the centroid does not.
   * A rigid grain whose shape RigidGrainMotion has located is not read from
   * its fill fraction: its surface lies at the signed distance d of the
   * node from its shape, gap = d - h_n Phi^{-1}(phi_g).
   *
   * With `Contact/Shape gap` (@p use_shapes), a grain that keeps its
   * shape (Transfer::get_field_keeps_shape(): an elastic disk or sphere
   * alone in its field) is read from its shape where it meets a located
   * rigid grain or a wall: its surface lies at the signed distance e of the
   * node from the shape placed at the grain's centre of mass (from the slot
   * masses), gap = d + e (at a wall on the box face, gap = e). The lattice
   * of its points turns with the grain, and its fill fractions move the
   * surface by a part of a cell from node to node as a rolling or spinning
   * grain turns; the shape does not. The shape is used while the grain is
   * strained little (the mass-weighted mean of its Green strain times its
   * radius at most a tenth of the cell size) and only where it agrees with
   * the fill within half a cell along the normal; elsewhere, and between
   * two deformable grains, the fills are read.
   */
  template <int dim>
  class GapEstimator
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * The gaps on @p grid, with the rigid grains (@p field_is_rigid per
     * field) where @p rigid_motion locates them, and with @p use_shapes the
     * fields that @p field_keeps_shape from the shapes of @p grain_parameters
     * (@p grains for their centroids); all allowed approaches are 0 unless
     * @p enabled.
     */
    GapEstimator(const BackgroundGrid<dim>               &grid,
                 const RigidGrainMotion<dim>             &rigid_motion,
                 const std::vector<bool>                 &field_is_rigid,
                 const std::vector<bool>                 &field_keeps_shape,
                 const std::vector<GrainInfo<dim>>       &grains,
                 const std::vector<GrainParameters<dim>> &grain_parameters,
                 const bool                               enabled,
                 const bool                               use_shapes);

    /** Whether the gaps are checked. */
    bool
    enabled() const
    {
      return is_enabled;
    }

    /**
     * The fill fractions and centroids of the owned slots of @p layout from
     * @p volumes (per slot sum_p V_p S_ip and its first moment,
     * Transfer::particles_to_grid()), and the distances from the shapes of
     * the grains that keep theirs, placed at their centres of mass from
     * @p masses (one per slot), if strained little enough according to
     * their points' sums @p shape_sums (move_shapes()), for a step of length
     * @p dt: the data of the allowed approaches until the next call.
     * Collective.
     */
    void
    compute(const GrainFieldLayout<dim> &layout,
            const std::vector<double>   &shape_sums,
            const VectorType            &masses,
            const VectorType            &volumes,
            const double                 dt);

    /**
     * The approach speeds the gaps allow the fields of the contact node
     * @p node (its masses, rigid flags and normals), whose first slot is
     * @p begin, into @p allowed (@p node.n entries).
     */
    void
    node_allowed_approach(const unsigned int      begin,
                          const ContactNode<dim> &node,
                          double                 *allowed) const;

    /** The approach speed the gap allows slot @p slot at box face @p face. */
    double
    wall_allowed_approach(const unsigned int slot,
                          const unsigned int face) const;

    /**
     * Where the wall at box face @p face reads the surface of slot
     * @p slot's grain from its shape: the speed towards the face (along its
     * outward normal) that the rotation of the grain about its centre of
     * mass gives the node's material; zero elsewhere. The rotation carries
     * that material along the shape's surface, which it does not bring
     * nearer the wall: the wall constrains the rest of the normal velocity.
     */
    double
    wall_turning_speed(const unsigned int slot, const unsigned int face) const;

  private:
    /**
     * Per field that keeps its shape, the displacement of its centre of
     * mass (from the owned slots of @p layout, summed over the ranks) from
     * its GrainInfo::centroid; zero for the others.
     */
    std::vector<Tensor<1, dim>>
    shape_displacements(const GrainFieldLayout<dim> &layout,
                        const VectorType            &masses) const;

    /**
     * Per field whether it keeps its shape and is strained little enough
     * for the shape to place its surface: the mass-weighted mean of the
     * Green strain |F^T F - I| / 2 of its points times its radius is at
     * most a tenth of the cell size. Also the centre of mass and angular
     * velocity of each such field from its points. @p shape_sums holds this
     * process's sums per field (Transfer::particles_to_grid()). Collective.
     */
    std::vector<bool>
    move_shapes(std::vector<double> shape_sums, const MPI_Comm communicator);

    /**
     * Whether the wall at box face @p face reads slot @p slot's surface from
     * its grain's shape (where that agrees with the fill within half a
     * cell), and the gap @p gap from the fill and the centroid.
     */
    bool
    wall_reads_shape(const unsigned int slot,
                     const unsigned int face,
                     double            &gap) const;

    /**
     * The signed distance e of slot @p slot's node from its field's shape
     * if the fill fraction @p fill puts the surface within half a cell of
     * it along @p normal (cell size @p h_normal there), else NaN.
     */
    double
    shape_distance(const unsigned int slot,
                   const double       fill,
                   const double       h_normal) const;

    /** The cell size along the unit vector @p normal. */
    double
    normal_cell_size(const Tensor<1, dim> &normal) const;

    const BackgroundGrid<dim>               &grid;
    const RigidGrainMotion<dim>             &rigid_motion;
    const std::vector<bool>                 &field_is_rigid;
    const std::vector<bool>                 &field_keeps_shape;
    const std::vector<GrainInfo<dim>>       &grains;
    const std::vector<GrainParameters<dim>> &grain_parameters;
    const bool                               is_enabled;
    const bool                               use_shapes;

    /**
     * Per owned slot the fraction of the node's support filled and, at
     * nodes on a box face, the centroid of its volume relative to the node
     * (for the walls); the step length.
     */
    std::vector<double> slot_fills;
    /**
     * Per owned slot of a rigid field at a node that reads the fills: the
     * signed distance of the node from the located shape (NaN if not
     * located).
     */
    std::vector<double> slot_distances;
    /**
     * Per owned slot of a field that keeps its shape, at a node that reads
     * the fills: the signed distance of the node from the shape at the
     * grain's centre of mass (NaN elsewhere).
     */
    std::vector<double>         slot_shape_distances;
    std::vector<Tensor<1, dim>> slot_centroids;
    /**
     * Per field that keeps its shape, the centre of mass and the angular
     * velocity (about z in 2D) of its points; per owned slot on a box face
     * of such a field, the velocity omega x r that this rotation gives the
     * centroid of its material (zero elsewhere).
     */
    std::vector<Point<dim>>     shape_centres;
    std::vector<Tensor<1, 3>>   shape_angular_velocities;
    std::vector<Tensor<1, dim>> slot_turning_velocities;
    double                      dt = 0.;
  };
} // namespace grainmpm

#endif
