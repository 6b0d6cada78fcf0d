// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_output_parameters_h
#define grainmpm_postprocess_output_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace grainmpm
{
  /**
   * Subsection "Output".
   */
  struct OutputParameters
  {
    std::string directory           = "results";
    double      interval            = 0.1;
    bool        write_particles     = true;
    bool        write_grid          = true;
    bool        write_grain_history = true;
    bool        write_contacts      = true;
    bool        test_mode           = false;

    void
    declare(ParameterHandler &prm);
    void
    check() const;
  };

  /**
   * Subsection "Checkpoint".
   */
  struct CheckpointParameters
  {
    unsigned int steps_between   = 0;
    double       minutes_between = 0.;
    unsigned int n_kept          = 2;
    std::string  resume_from;
    bool         replace_other_checkpoints = false;
    /**
     * On a resume with another mass scaling: divide the velocities by the
     * square root of the mass ratio (keeping the kinetic energy) instead
     * of keeping them.
     */
    bool scale_velocities_with_mass = false;

    void
    declare(ParameterHandler &prm);
  };
} // namespace grainmpm

#endif
