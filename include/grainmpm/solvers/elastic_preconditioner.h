// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_solvers_elastic_preconditioner_h
#define grainmpm_solvers_elastic_preconditioner_h

#include <grainmpm/base/config.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <vector>

namespace grainmpm
{
  /**
   * An assembled approximation of the Jacobian of the implicit theta
   * residual, inverted approximately by one algebraic multigrid V-cycle
   * (Trilinos ML through TrilinosWrappers::PreconditionAMG). The outer
   * solver stays Jacobian-free; this only replaces the probed diagonal.
   *
   * The residual (ThetaResidual) is R = P R_raw + (V - P V) with the
   * frozen contact projection P, R_raw = V - v^n - dt (f(v^theta) / m + g)
   * and v^theta = (1 - theta) v^n + theta P V. Linearising the internal
   * force of a linear elastic grain, df / dV = -theta^2 dt K P with the
   * small-strain stiffness K = sum_p V_p B_p^T C B_p, and holding the
   * contact reference velocities fixed (the simplified Jacobian of the
   * probed diagonal), P acts slot by slot and
   *
   *   J = M_L^-1 A,  A = P M + M_L (I - P) + theta^2 dt^2 P K P,
   *
   * with M the grid mass matrix (lumped M_L, or blended with the
   * consistent mass) and M_L the lumped mass that divides the residual
   * (P acts slot by slot and commutes with M_L; for the lumped mass
   * A = M_L + theta^2 dt^2 P K P). This class assembles A over the slots of
   * every deformable grain (block diagonal by grain: grains couple only
   * through the contact law, which P expresses by removing the constrained
   * directions) and applies z = A^-1 (M r) approximately. P K P is
   * symmetric where P is (free, frictionless and sticking slots); with
   * Coulomb sliding P is not (the tangential correction follows the
   * normal one), and neither is A at
   * those few rows. Slots that are
   * not unknowns (rigid, too light) have R = V - something, J = I: their
   * rows are M_ss delta.
   *
   * What A leaves out: the geometric stiffness (sigma^n and the volume
   * change), plasticity (the elastic tangent is used), the consistent part
   * of a blended mass matrix, and the coupling of a contact pair through
   * the centre-of-mass reference velocity. GMRES corrects for these.
   *
   * In parallel the rows are the locally owned unknowns of the slot
   * layout; particles add to ghost rows, which Trilinos sends to their
   * owners.
   */
  template <int dim>
  class ElasticPreconditioner
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * Assemble A and set up the multigrid hierarchy.
     *
     * @p cache gives the particles' entries (slots, shape values and
     * gradients), @p models the constitutive model of each particle in
     * cache order (nullptr for rigid grains), @p volumes their volumes at
     * t^n, @p mass_matrix the grid mass matrix M (lumped or blended).
     * @p lumped_masses holds the lumped mass m_s of each owned slot by
     * which the residual is divided (for slots that are not unknowns any
     * positive number), @p unknown says for each owned and ghost slot
     * whether it is an unknown of the elastic system (deformable, not
     * light), @p projections gives its frozen projection P_s as a
     * dim x dim tensor. @p factor is theta^2 dt^2. @p layout_vector is a
     * vector with the layout of the unknowns (its partitioner is used).
     * Without @p new_pattern the sparsity pattern of the last call is
     * kept (the same slots and points, another contact status).
     */
    void
    initialize(const TransferCache<dim>                          &cache,
               const std::vector<const ConstitutiveModel<dim> *> &models,
               const std::vector<double>                         &volumes,
               const MassMatrix<dim>                             &mass_matrix,
               const std::vector<double>                         &lumped_masses,
               const std::vector<bool>                           &unknown,
               const std::vector<Tensor<2, dim>>                 &projections,
               const double                                       factor,
               const VectorType                                  &layout_vector,
               const bool new_pattern = true);

    /** @p dst = A^-1 (M @p src), approximately (one V-cycle). */
    void
    vmult(VectorType &dst, const VectorType &src) const;

    /** The assembled matrix (for tests). */
    const TrilinosWrappers::SparseMatrix &
    get_matrix() const
    {
      return matrix;
    }

  private:
    /**
     * The pattern of A over the owned and ghost unknowns in local numbers
     * (CSR: row_start, columns; global_columns the global numbers), and
     * the values being assembled.
     */
    std::vector<unsigned int>            row_start;
    std::vector<unsigned int>            columns;
    std::vector<types::global_dof_index> global_columns;
    std::vector<double>                  values;
    TrilinosWrappers::SparseMatrix       matrix;
    TrilinosWrappers::PreconditionAMG    amg;
    std::vector<double>                  dof_weights;
    mutable VectorType                   weighted;
  };
} // namespace grainmpm

#endif
