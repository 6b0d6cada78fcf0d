// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_transfer_transfer_options_h
#define grainmpm_transfer_transfer_options_h

#include <grainmpm/base/config.h>

#include <string>

namespace grainmpm
{
  /**
   * What a time integrator asks of the transfer beyond the shape
   * functions: Transfer never asks which scheme it serves.
   */
  struct TransferOptions
  {
    /**
     * A deformable material point that moves more than a cell in one step
     * is a blow-up (the explicit scheme: no wave the step resolves travels
     * that far).
     */
    bool limit_move_to_one_cell = false;
    /**
     * The advice of the error message of a material point whose state is
     * not finite, or that blows up.
     */
    std::string divergence_advice = "Use a smaller time step.";
    /**
     * Gather the ParticleSums in grid_to_particles(): the last pass over
     * the particles of a step that sees the final velocities, positions,
     * stresses and volumes (the explicit update-stress-first step).
     */
    bool gather_particle_sums = false;
    /**
     * Book LedgerIncrements::leapfrog_energy_change in grid_to_particles()
     * (the explicit scheme with Stress update = USL).
     */
    bool book_leapfrog_energy_change = false;
  };
} // namespace grainmpm

#endif
