// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_implicit_elastic_preconditioner_h
#define grainmpm_time_integration_implicit_elastic_preconditioner_h

#include <grainmpm/base/config.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/solvers/sparse_cholesky.h>
#include <grainmpm/time_integration/implicit/slot_projection.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/mass_matrix.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <deal.II/base/partitioner.h>
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
   * (Trilinos ML through TrilinosWrappers::PreconditionAMG) or, on one
   * process, by a sparse Cholesky factorisation of its symmetric part
   * (SparseCholesky; set_inverse()). The outer solver stays
   * Jacobian-free; this only replaces the probed diagonal.
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

    /** How A is inverted. */
    enum class Inverse
    {
      /** One V-cycle of smoothed aggregation (any number of processes). */
      multigrid,
      /**
       * A sparse Cholesky factorisation of (A + A^T) / 2 (one process),
       * or the V-cycle where that is not positive definite.
       */
      cholesky
    };

    /** Choose the inverse of A for the next setup() (default multigrid). */
    void
    set_inverse(const Inverse new_inverse)
    {
      inverse = new_inverse;
    }

    /**
     * Set up the preconditioner for the contact status frozen at present:
     * the unknowns among the owned and ghost slots of @p layout, the
     * linear part P of the frozen projection (SlotProjection::probe()
     * through @p linear_projection), the lumped masses, then A and its
     * multigrid hierarchy or factorisation.
     *
     * @p owned_unknown says for each owned slot whether it is an unknown
     * of the elastic system (deformable, not light), @p masses holds the
     * lumped mass m_s by which the residual is divided (a vector of the
     * slot layout, one entry per slot). @p cache gives the particles'
     * entries (slots, shape values and gradients), @p models the
     * constitutive model of each particle in cache order (nullptr for
     * rigid grains), @p volumes their volumes at t^n, @p mass_matrix the
     * grid mass matrix M (lumped or blended). @p factor is
     * theta^2 dt^2. @p layout_vector is a vector with the layout of the
     * unknowns (its partitioner is used). Without @p new_pattern the
     * groups of SlotProjection and the sparsity pattern of the last call
     * are kept (the same slots and points, another contact status).
     */
    void
    setup(const GrainFieldLayout<dim>                       &layout,
          const std::vector<bool>                           &owned_unknown,
          const VectorType                                  &masses,
          const typename SlotProjection<dim>::LinearMap     &linear_projection,
          const TransferCache<dim>                          &cache,
          const std::vector<const ConstitutiveModel<dim> *> &models,
          const std::vector<double>                         &volumes,
          const MassMatrix<dim>                             &mass_matrix,
          const double                                       factor,
          const VectorType                                  &layout_vector,
          const bool                                         new_pattern);

    /**
     * @p dst = A^-1 (M @p src), approximately (one V-cycle) or with the
     * factorisation of the symmetric part of A.
     */
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
     * Assemble A with the projection of setup() and factorise it or set up
     * its multigrid hierarchy. @p masses holds the lumped mass of each
     * owned and ghost slot (for slots that are not unknowns any positive
     * number),
     * @p unknown says for each owned and ghost slot whether it is an
     * unknown; the other arguments are those of setup().
     */
    void
    initialize(const TransferCache<dim>                          &cache,
               const std::vector<const ConstitutiveModel<dim> *> &models,
               const std::vector<double>                         &volumes,
               const MassMatrix<dim>                             &mass_matrix,
               const std::vector<double>                         &masses,
               const std::vector<bool>                           &unknown,
               const double                                       factor,
               const VectorType                                  &layout_vector,
               const bool                                         new_pattern);

    /**
     * The pattern of the raw matrix (raw_start, raw_columns): the
     * unknown slots that share a deformable particle with each slot.
     */
    void
    build_raw_pattern(const TransferCache<dim>                          &cache,
                      const std::vector<const ConstitutiveModel<dim> *> &models,
                      const std::vector<bool> &unknown,
                      const unsigned int       n_local_slots);

    /**
     * The raw blocks: theta^2 dt^2 K (@p factor K) and the consistent
     * mass off the diagonal (blended mass only).
     */
    void
    assemble_raw_blocks(
      const TransferCache<dim>                          &cache,
      const std::vector<const ConstitutiveModel<dim> *> &models,
      const std::vector<double>                         &volumes,
      const MassMatrix<dim>                             &mass_matrix,
      const std::vector<bool>                           &unknown,
      const double                                       factor);

    /**
     * The pattern of A in local numbers (row_start, columns) from the raw
     * pattern widened by the groups of the projection, and the offset of
     * each raw block in its row (raw_offsets).
     */
    void
    build_pattern(const std::vector<bool> &unknown,
                  const unsigned int       n_owned_slots,
                  const unsigned int       n_local_slots);

    /** global_columns, the Trilinos sparsity pattern and the matrix. */
    void
    reinit_matrix(const Utilities::MPI::Partitioner &partitioner);

    /** A[@p row slot][@p column slot] += @p block, in values. */
    void
    add_block(const unsigned int    row,
              const unsigned int    column,
              const Tensor<2, dim> &block);

    /** The columns of Q = M_L P M_L^-1 (q_start, q_rows, q_blocks). */
    void
    setup_q_blocks(const std::vector<double> &masses,
                   const unsigned int         n_local_slots);

    /**
     * M_L (I - P) and Q D, D the diagonal of M, on the owned slots, m_s
     * delta for the slots that are not unknowns, and the slots left alone
     * by P (plain); the weights of vmult().
     */
    void
    assemble_mass_terms(const MassMatrix<dim>     &mass_matrix,
                        const std::vector<double> &masses,
                        const std::vector<bool>   &unknown,
                        const unsigned int         n_owned_slots);

    /** Q (theta^2 dt^2 K) P + Q M_C, M_C the consistent mass off the diagonal.
     */
    void
    assemble_stiffness_terms(const std::vector<bool> &unknown,
                             const unsigned int       n_local_slots);

    /** The smoothed-aggregation hierarchy of the matrix. */
    void
    setup_multigrid(const unsigned int n_owned);

    /** The linear part of the frozen projection. */
    SlotProjection<dim> projection;
    /**
     * The columns of Q (for each slot a, the rows r with Q_ra != 0 and
     * Q_ra), and the slots whose raw blocks go in unchanged.
     */
    std::vector<unsigned int>   q_start;
    std::vector<unsigned int>   q_rows;
    std::vector<Tensor<2, dim>> q_blocks;
    std::vector<bool>           plain;
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
    Inverse                              inverse = Inverse::multigrid;
    TrilinosWrappers::PreconditionAMG    amg;
    SparseCholesky                       cholesky;
    /** The last setup factorised A (else it set up the V-cycle). */
    bool                factorised = false;
    std::vector<double> dof_weights;
    mutable VectorType  weighted;
  };
} // namespace grainmpm

#endif
