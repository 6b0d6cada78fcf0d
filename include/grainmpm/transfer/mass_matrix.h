// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_mass_matrix_h
#define grainmpm_transfer_mass_matrix_h

#include <grainmpm/base/config.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace grainmpm
{
  /**
   * The grid mass matrix of one step, matrix-free:
   *
   *   M = (1 - alpha) M_L + alpha M_C
   *
   * on the slots of deformable grains, with M_L the lumped (diagonal) mass
   * m_i = sum_p m_p S_ip and M_C the consistent mass
   * (M_C v)_i = sum_p m_p S_ip sum_j S_jp v_j, which is particle to grid
   * of grid to particle and couples only slots of the same field (the
   * entries of a particle all belong to its field). Slots of rigid grains
   * keep the lumped mass. alpha = 0 is the lumped mass of the explicit
   * scheme.
   *
   * Light slots, with at most 1e-6 of the largest particle mass
   * (light_mass_threshold()), are lumped too: the consistent entries that
   * couple them to other slots are moved onto the diagonals, which keeps M
   * symmetric with the same row sums. Their share of a point's mass is
   * round-off, and the implicit scheme does not apply forces to them
   * (ThetaResidual); coupled to their neighbours, the equation
   * (M (V - v^n))_s = 0 of such a slot would set its velocity change to
   * -alpha / (1 - alpha) times its neighbours' (their weighted mean), and
   * the force the stress puts on it, which is not applied, would do work.
   *
   * M_C has the row sums m_i and is symmetric, so every column of M sums
   * to the lumped mass too: sum_i (M v)_i = sum_i m_i v_i per component,
   * and a force balance written with M conserves momentum exactly as one
   * written with M_L does. 0 < v.M_C v <= v.M_L v (Jensen's inequality per
   * particle), so M is symmetric positive definite for alpha < 1 with
   * eigenvalues of M_L^{-1} M in [1 - alpha, 1]: the grid-scale
   * (checkerboard) modes that M_C barely sees keep the mass 1 - alpha.
   *
   * The consistent part removes the smoothing of the lumped mass: with
   * M_L, the particle-to-grid velocity p / m averages neighbouring
   * particles, and the FLIP transfer back loses the energy of the
   * difference at every step; with M the grid velocity is (for alpha -> 1)
   * the least-squares fit of the particle velocities (Burgess, Sulsky &
   * Brackbill 1992; Love & Sulsky 2006).
   */
  template <int dim>
  class MassMatrix
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /**
     * Set up the matrix of the particles of @p particle_handler with the
     * cache and slots of @p transfer (after Transfer::reinit()), the lumped
     * slot masses @p lumped_masses (which must live as long as this object
     * is used) and the consistent fraction @p fraction (alpha, in [0, 1]).
     */
    void
    reinit(const Transfer<dim>                   &transfer,
           const Particles::ParticleHandler<dim> &particle_handler,
           const VectorType                      &lumped_masses,
           const double                           fraction);

    /**
     * Slots with no more mass than this are light: 1e-6 of the largest
     * particle mass.
     */
    double
    light_mass_threshold() const
    {
      return light_threshold;
    }

    /** Whether M is the lumped mass (alpha = 0). */
    bool
    is_lumped() const
    {
      return fraction == 0.;
    }

    /** alpha. */
    double
    get_fraction() const
    {
      return fraction;
    }

    /**
     * @p dst = M @p src (dim numbers per slot). @p src needs no ghost
     * values; they are read here and left as they were. Collective unless
     * lumped.
     */
    void
    vmult(VectorType &dst, const VectorType &src) const;

    /**
     * Solve M @p velocities = @p momenta by conjugate gradients with the
     * diagonal of M as preconditioner, starting from the lumped solution
     * p / m, to a residual of 1e-12 of |p|. Returns the number of
     * iterations (0 when lumped). Collective.
     */
    unsigned int
    solve(const VectorType &momenta, VectorType &velocities) const;

    /**
     * This rank's share of 1/2 v . M v over the owned slots of deformable
     * grains, for @p velocities. Collective unless lumped.
     */
    double
    local_kinetic_energy(const VectorType &velocities) const;

    /** The particle masses in cache order. */
    const std::vector<double> &
    get_particle_masses() const
    {
      return particle_masses;
    }

    /**
     * The shape values of the consistent part per cache entry: S_ip, zero
     * at lumped slots. An off-diagonal entry of M is
     * alpha sum_p m_p S_ip S_jp over these.
     */
    const std::vector<double> &
    get_consistent_shapes() const
    {
      return consistent_shapes;
    }

    /** The diagonal of M (dim equal entries per owned slot). */
    const VectorType &
    get_diagonal() const
    {
      return diagonal;
    }

  private:
    /** M_C @p src into @p dst (no compress, ghosts of @p src read). */
    void
    add_consistent(const VectorType &src, VectorType &dst) const;

    const Transfer<dim> *transfer        = nullptr;
    const VectorType    *lumped_masses   = nullptr;
    double               fraction        = 0.;
    double               light_threshold = 0.;
    /** m_p of each particle in cache order, 0 for rigid ones. */
    std::vector<double> particle_masses;
    /** Whether each owned slot belongs to a rigid grain. */
    std::vector<bool> slot_rigid;
    /**
     * Whether each local slot (owned and ghost) has the lumped mass row:
     * light, or rigid.
     */
    std::vector<bool> slot_lumped;
    /** S_ip of each cache entry, zero where the slot is lumped. */
    std::vector<double> consistent_shapes;
    /** Per particle, the sum of S_ip over its lumped slots. */
    std::vector<double> lumped_weights;
    /** The diagonal of M per unknown (dim per slot). */
    VectorType diagonal;
  };
} // namespace grainmpm

#endif
