// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_step_statistics_h
#define grainmpm_base_step_statistics_h

#include <grainmpm/base/config.h>

#include <deal.II/base/mpi.h>

#include <deal.II/particles/property_pool.h>

#include <string>

namespace grainmpm
{
  /**
   * What happened to the material points and the contact nodes in one
   * step (counted on each rank, reduced by StepStatistics::reduce()).
   */
  struct ParticleEvents
  {
    /** Contact nodes where the projection corrected a field. */
    unsigned int n_contact_nodes = 0;
    /** Particles removed through open faces in this step. */
    types::particle_index n_removed = 0;
    /**
     * Deformable particles put back on a closed face that the interpolated
     * velocity had carried less than half a cell through.
     */
    types::particle_index n_held_at_walls = 0;
    /** Largest particle speed after the step. */
    double max_speed = 0.;
    /** True if some particle changed cells and the handler was sorted. */
    bool sorted = false;
  };



  /** How the nonlinear solve of one implicit step went. */
  struct SolverCounts
  {
    /** False if an implicit step failed; the particles are then untouched. */
    bool converged = true;
    /** Why an implicit step failed. */
    std::string failure;
    /**
     * The step failed although its Newton solve converged: it was
     * rejected for its accuracy (ImplicitTheta::energy_error()).
     */
    bool rejected_for_accuracy = false;
    /**
     * The Newton solve failed at its first iterate: the residual with the
     * first contact status was not finite.
     */
    bool failed_at_first_iterate = false;
    /** Newton iterations of the accepted solve. */
    unsigned int newton_iterations = 0;
    /** Krylov iterations summed over the Newton iterations. */
    unsigned int linear_iterations = 0;
    /** Residual evaluations of the step (all attempts). */
    unsigned int residual_evaluations = 0;
    /** Final RMS(R) / U of the accepted solve (U: velocity scale). */
    double residual_norm = 0.;
    /** Changes of the contact status during the accepted solve. */
    unsigned int status_changes = 0;
    /** Attempts rejected before this step was accepted. */
    unsigned int rejected = 0;
    /**
     * Explicit sub-steps that advanced this step after its implicit solve
     * failed (`Time stepping/Explicit fallback`; 0 otherwise).
     */
    unsigned int explicit_substeps = 0;
    /**
     * The estimated relative error of an accepted implicit step
     * (StepErrorEstimator), or negative if there is none.
     */
    double step_error = -1.;
    /**
     * The centring of an implicit step: `Time stepping/Theta`, or
     * `Quasi-static theta` after a quasi-static step; 0 for explicit steps.
     */
    double theta = 0.;
  };



  /**
   * The step's increments of the energy ledger (EnergyHistory): the terms
   * that the energies of the particles alone do not show.
   */
  struct LedgerIncrements
  {
    /**
     * Implicit scheme: change of the grid energy 1/2 sum m v^2 + sum V W
     * of the deformable grains over the step, from the particle-to-grid
     * velocities (so including the contact pass on v^n) to the end
     * velocities: the time integrator's share of the energy balance. With
     * transfer_energy_change it adds up to the change of the particles'
     * kinetic plus elastic energy (without gravity and removed particles).
     */
    double grid_energy_change = 0.;
    /**
     * Both schemes: what the grid-to-particle velocity update adds to the
     * kinetic energy of the deformable particles beyond the change of the
     * grid kinetic energy it maps, sum_p 1/2 m_p |v_p|^2 (after - before)
     * - sum_s 1/2 m_s (|v_s^new|^2 - |v_s^p2g|^2). For FLIP it is
     * -1/2 (sum_s m_s |dv_s|^2 - sum_p m_p |sum_s S_sp dv_s|^2) <= 0: the
     * lumped-mass loss of Cummins & Brackbill, which the grid cannot see.
     */
    double transfer_energy_change = 0.;
    /**
     * Both schemes: the step's plastic work sum_p V_p sigma : de_p of the
     * deformable particles (>= 0).
     */
    double plastic_work = 0.;
    /**
     * Both schemes: the volume term of the elastic energy,
     * sum_p 1/2 (W(sigma_p^n) + W(sigma_p^{n+1})) (V_p^{n+1} - V_p^n),
     * W = 1/2 sigma : C^{-1} : sigma, over the deformable particles. V W
     * changes by the mean volume times the change of W, which is the
     * elastic work of the stresses, plus this term, which is not work: a
     * hypoelastic material stores the work of its stresses, and V W
     * measures it only to first order in the strain. Booked so that the
     * balance residual holds the numerical gains and losses alone.
     */
    double hypoelastic_correction = 0.;
    /**
     * Both schemes: the work the contact, wall and rigid-grain constraints
     * of the step do on the deformable grains, split into what rigid grains
     * and walls put in (boundary_work: the reaction on the slots of a node
     * times the velocity of its rigid partner; walls are at rest) and what
     * friction takes out (friction_work >= 0 with Coulomb friction, 0 for
     * frictionless constraints). The reaction on a slot is m_s times the
     * change the constraints make to its end velocity; it works on the
     * velocity that moves the particles (v^theta implicit, v^{n+1}
     * explicit).
     */
    double friction_work = 0.;
    double boundary_work = 0.;
    /**
     * Explicit scheme: the energy the leapfrog's exchange between kinetic
     * and strain energy adds (<= 0), sum_p 1/2 m_p |dv_p|^2 -
     * sum_s 1/2 m_s |dv_s|^2 with the step's grid velocity change
     * dv_s = v_s^{n+1} - v_s^n (forces and constraints) and its
     * interpolation dv_p = sum_s S_sp dv_s to the deformable particles
     * (Transfer::grid_to_particles()): the kinetic energy of the
     * grid-scale part of dv that the particles' strain does not see. Booked
     * with Stress update = USL only: USF and MUSL take the strain from
     * another velocity than the one the forces changed, and their exchange
     * stays in the balance. Zero in the implicit scheme, which books the
     * grid energy change instead.
     */
    double leapfrog_energy_change = 0.;
  };



  /**
   * The sums over the particles that the energy history needs, when a
   * pass of the step over the particles could gather them.
   */
  struct ParticleSums
  {
    /**
     * Whether the step gathered the particle sums below in its last pass
     * over the particles (the explicit scheme with the update-stress-first
     * order, whose grid-to-particle pass sees the final velocities,
     * positions, stresses and volumes); otherwise EnergyHistory::compute()
     * visits the particles again.
     */
    bool has_particle_sums = false;
    /**
     * Over the deformable particles that remain after the step: the kinetic
     * energy sum 1/2 m |v|^2, the elastic energy sum V W(sigma), the
     * momentum sum m v and the first moment sum m x (components beyond the
     * dimension zero).
     */
    double kinetic_energy  = 0.;
    double elastic_energy  = 0.;
    double momentum[3]     = {0., 0., 0.};
    double first_moment[3] = {0., 0., 0.};
  };



  /**
   * What one step did, by meaning: what happened to the points and nodes
   * (events), how the solve went (solver), the ledger increments (ledger)
   * and the particle sums (sums).
   */
  struct StepStatistics
  {
    ParticleEvents   events;
    SolverCounts     solver;
    LedgerIncrements ledger;
    ParticleSums     sums;

    /**
     * Add up (largest speed: maximum; sorted: or) what each rank counted
     * of its particles and slots: contact nodes, removed and held points,
     * the transfer energy change, the plastic, friction and boundary work,
     * the leapfrog energy change and the particle sums. Collective: two
     * reductions.
     */
    void
    reduce(const MPI_Comm communicator);
  };
} // namespace grainmpm

#endif
