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
   * The linear part P of the frozen contact and wall projection of the
   * implicit residual, row by row over the owned and ghost slots of the
   * layout: (P z)_a = sum_k blocks[k] z_partners[k] for k in
   * [start[a], start[a + 1]), the partners being slots of the node of a
   * (a itself among them). Contact couples the fields of a node through
   * their centre-of-mass (or rigid) reference velocity; walls act on the
   * slot alone. groups[group_start[a] .. group_start[a + 1]) lists the
   * slots of the node of a that this rank knows (all of them at owned
   * nodes): the couplings P may have whatever the contact status.
   */
  template <int dim>
  struct SlotProjection
  {
    std::vector<unsigned int>   start;
    std::vector<unsigned int>   partners;
    std::vector<Tensor<2, dim>> blocks;
    std::vector<unsigned int>   group_start;
    std::vector<unsigned int>   groups;
  };



  /**
   * An assembled approximation of the Jacobian of the implicit theta
   * residual, inverted approximately by one algebraic multigrid V-cycle
   * (Trilinos ML through TrilinosWrappers::PreconditionAMG). The outer
   * solver stays Jacobian-free; this only replaces the probed diagonal.
   *
   * The residual (ThetaResidual) is R = P R_raw + (V - P V) with the
   * frozen contact projection P, R_raw = M_L^-1 M (V - v^n) - dt (f(v^theta)
   * / m + g) and v^theta = (1 - theta) v^n + theta P V. Linearising the
   * internal force of a linear elastic grain, df / dV = -theta^2 dt K P
   * with the small-strain stiffness K = sum_p V_p B_p^T C B_p, gives
   *
   *   J = M_L^-1 A,  A = Q M + M_L (I - P) + theta^2 dt^2 Q K P,
   *   Q = M_L P M_L^-1,
   *
   * with M the grid mass matrix (lumped M_L, or blended with the
   * consistent mass) and M_L the lumped mass that divides the residual.
   * P is the linear part of the full frozen projection (SlotProjection):
   * at a contact node it couples the fields through their common reference
   * velocity, so that A couples the grains that touch; for frictionless
   * contact, sticking and walls P is M_L-orthogonal, Q = P^T and A is
   * symmetric. With Coulomb sliding the tangential correction follows the
   * normal one and P is not; that friction term is left out of P here
   * (ContactStatus::apply_symmetric_linear_part), which keeps A symmetric for
   * the smoothed aggregation. K is block diagonal by grain. Slots that are not
   * unknowns (rigid, too light) have R = V - something, J = I: their rows are
   * m_s delta.
   *
   * What A leaves out: the friction of sliding slots, the geometric
   * stiffness (sigma^n, the volume change and the stress rotation),
   * plasticity (the elastic tangent is used), and at nodes owned
   * by another MPI rank the couplings to the fields this rank does not
   * see there. GMRES corrects for these.
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
     * @p masses holds the lumped mass m_s of each owned and ghost slot by
     * which the residual is divided (for slots that are not unknowns any
     * positive number), @p unknown says for each owned and ghost slot
     * whether it is an unknown of the elastic system (deformable, not
     * light), @p projection the linear part of the frozen projection.
     * @p factor is theta^2 dt^2. @p layout_vector is a
     * vector with the layout of the unknowns (its partitioner is used).
     * Without @p new_pattern the sparsity pattern of the last call is
     * kept (the same slots and points, another contact status).
     */
    void
    initialize(const TransferCache<dim>                          &cache,
               const std::vector<const ConstitutiveModel<dim> *> &models,
               const std::vector<double>                         &volumes,
               const MassMatrix<dim>                             &mass_matrix,
               const std::vector<double>                         &masses,
               const std::vector<bool>                           &unknown,
               const SlotProjection<dim>                         &projection,
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
    std::vector<unsigned int>            raw_start;
    std::vector<unsigned int>            raw_columns;
    std::vector<Tensor<2, dim>>          raw_stiffness;
    std::vector<double>                  raw_mass;
    std::vector<unsigned int>            raw_offsets;
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
