// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_grain_contact_h
#define grainmpm_contact_grain_contact_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/transfer/grain_field_layout.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <vector>

namespace grainmpm
{
  using namespace dealii;

  /**
   * The Bardenhagen-Brackbill-Sulsky contact between the velocity fields of
   * grains that meet at a grid node (seed eqs. 5-6, reference/physics.md
   * sections 3.3-3.9), and the rigid walls on the faces of the box
   * (section 2.5).
   *
   * At a contact node every field g gets the normal
   * n_g = (g_g - sum_{k != g} g_k) / |...| from the mass gradients
   * g_g = sum_p m_p grad S_ip, so that two fields get exactly antiparallel
   * normals. Field g approaches iff (v_g - v_cm) . n_g > 0, v_cm being the
   * centre-of-mass velocity of the node (or the velocity of a rigid field,
   * which has infinite mass); then the normal part of v_g - v_cm is removed
   * and the tangential part reduced by Coulomb friction (stick if
   * mu D >= |dv_t|, else slip by mu D). Receding fields are left alone.
   * With two deformable fields this conserves the node's momentum exactly.
   * With three or more the normals cannot all be pairwise antiparallel; the
   * projection then alternates with a common velocity shift that restores
   * the node's momentum, until no field approaches, so momentum is
   * conserved at every contact node and no field is left approaching.
   */
  template <int dim>
  class GrainContact
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * @p field_is_rigid says for each field whether it belongs to a rigid
     * grain.
     */
    GrainContact(const ContactParameters   &parameters,
                 const BackgroundGrid<dim> &grid,
                 const std::vector<bool>   &field_is_rigid);

    /**
     * Contact normals (dim numbers per slot) at the contact nodes of
     * @p layout from the mass gradients @p mass_gradients; zero elsewhere.
     */
    void
    compute_normals(const GrainFieldLayout<dim> &layout,
                    const VectorType            &mass_gradients,
                    VectorType                  &normals) const;

    /**
     * Apply the contact projection to @p velocities (dim per slot) at every
     * contact node. Sets @p node_in_contact[node] for nodes where a field
     * was corrected, and returns their number.
     */
    unsigned int
    apply_contact(const GrainFieldLayout<dim> &layout,
                  const VectorType            &masses,
                  const VectorType            &normals,
                  VectorType                  &velocities,
                  std::vector<unsigned char>  &node_in_contact) const;

    /**
     * Apply the wall conditions of the box faces to the deformable fields
     * at boundary nodes.
     */
    void
    apply_walls(const GrainFieldLayout<dim> &layout,
                VectorType                  &velocities) const;

    /**
     * The projection at one node with @p n_fields fields: masses, rigid
     * flags, normals, and the velocities to correct in place. Returns true
     * if some field was corrected. Exposed for the unit tests.
     */
    static bool
    project_node(const unsigned int    n_fields,
                 const double         *masses,
                 const bool           *rigid,
                 const Tensor<1, dim> *normals,
                 Tensor<1, dim>       *velocities,
                 const ContactModel    model,
                 const double          friction_coefficient);

    /**
     * The unilateral wall condition with outward wall normal @p normal
     * (pointing into the wall) applied to @p velocity.
     */
    static void
    apply_wall(const BoundaryCondition &condition,
               const Tensor<1, dim>    &normal,
               Tensor<1, dim>          &velocity);

    /** Outward unit normal of box face @p face (x-, x+, y-, ...). */
    static Tensor<1, dim>
    face_normal(const unsigned int face)
    {
      Tensor<1, dim> normal;
      normal[face / 2] = (face % 2 == 0) ? -1. : 1.;
      return normal;
    }

  private:
    const ContactParameters   &parameters;
    const BackgroundGrid<dim> &grid;
    const std::vector<bool>   &field_is_rigid;
  };
} // namespace grainmpm

#endif
