// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_gap_estimator_h
#define grainmpm_contact_gap_estimator_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_law.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/shape_functions.h>

#include <deal.II/lac/la_parallel_vector.h>

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
   * h_n the cell size along the normal; a wall gives
   * gap = h (1 - sqrt(phi_g)). Two flat blocks in contact have
   * phi_a + phi_b = 1, gap 0.
   */
  template <int dim>
  class GapEstimator
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /** The gaps on @p grid; all allowed approaches are 0 unless @p enabled. */
    GapEstimator(const BackgroundGrid<dim> &grid, const bool enabled);

    /** Whether the gaps are checked. */
    bool
    enabled() const
    {
      return is_enabled;
    }

    /**
     * The fill fractions of the owned slots of @p layout from the slot
     * volumes @p volumes (sum_p V_p S_ip), for a step of length @p dt: the
     * data of the allowed approaches until the next call.
     */
    void
    compute(const GrainFieldLayout<dim> &layout,
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
                          const unsigned int face) const
    {
      if (!is_enabled)
        return 0.;
      // The in-box half of the support along the wall normal.
      return grid.cell_size()[face / 2] *
             HatKernel::inverse_half_integral(slot_fills[slot]) / dt;
    }

  private:
    const BackgroundGrid<dim> &grid;
    const bool                 is_enabled;

    /** Fill fraction per owned slot, and the step length. */
    std::vector<double> slot_fills;
    double              dt = 0.;
  };
} // namespace grainmpm

#endif
