// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_time_stepping_parameters_h
#define grainmpm_time_integration_time_stepping_parameters_h

#include <grainmpm/base/config.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace grainmpm
{
  /**
   * Order of the explicit stress update.
   */
  enum class StressUpdate
  {
    usf,
    musl,
    usl
  };

  /**
   * The time integration schemes (subsection "Time stepping").
   */
  enum class TimeSteppingScheme
  {
    explicit_leapfrog,
    implicit_theta
  };

  /**
   * How the particles get their new velocity from the grid.
   */
  enum class VelocityUpdate
  {
    flip,
    pic,
    blend
  };

  /**
   * The grid mass matrix of the implicit scheme (see MassMatrix).
   */
  enum class MassMatrixType
  {
    lumped,
    blended
  };

  /**
   * Subsection "Time stepping".
   */
  struct TimeSteppingParameters
  {
    std::string        scheme_text = "explicit leapfrog";
    TimeSteppingScheme scheme      = TimeSteppingScheme::explicit_leapfrog;
    /**
     * Factor alpha >= 1 on the densities (inertia), with gravity divided
     * by it (Parameters::apply_mass_scaling()).
     */
    double mass_scaling = 1.;
    /** Centring parameter of the implicit scheme, in [1/2, 1]. */
    double theta = 0.5;
    /** Smallest step the implicit failure policy may cut to (0: auto). */
    double minimum_time_step = 0.;
    /** Cut dt on a failed implicit step and grow it back afterwards. */
    bool adaptive_time_stepping = true;
    /** Consecutive easy steps before dt is doubled back. */
    unsigned int steps_before_growth = 2;
    /**
     * Largest step the implicit steps may grow to beyond the step of
     * `Time step` or `CFL number` (0: maximum_cfl_number decides).
     */
    double maximum_time_step = 0.;
    /**
     * Without a maximum_time_step: the largest implicit step as a multiple
     * of h / c, the explicit stability limit at rest (0: no growth).
     */
    double maximum_cfl_number = 250.;
    /**
     * Largest displacement of a grain (its rigid-body motion) in a step
     * grown beyond the nominal one, as a fraction of the smallest cell
     * size.
     */
    double maximum_displacement = 0.1;
    /**
     * With growth beyond the nominal step: the largest energy an implicit
     * step may create, as a fraction of the grid energy, before it is
     * rejected (0: no such check).
     */
    double energy_error = 1e-3;
    /**
     * With growth beyond the nominal step: the relative error per step
     * (StepErrorEstimator) that bounds the next step (0: no such bound).
     */
    double step_error_tolerance = 0.05;
    /**
     * With growth beyond the nominal step: the centring of a step that
     * follows a quasi-static step, max(theta, this) (0: theta throughout).
     */
    double quasi_static_theta = 0.6;
    /**
     * Advance a step that the implicit solve cannot take at the explicit
     * stable step by explicit leapfrog sub-steps.
     */
    bool           explicit_fallback    = true;
    std::string    stress_update_text   = "USF";
    StressUpdate   stress_update        = StressUpdate::usf;
    double         end_time             = 1.;
    double         time_step            = 0.;
    double         cfl_number           = 0.25;
    std::string    velocity_update_text = "FLIP";
    VelocityUpdate velocity_update      = VelocityUpdate::flip;
    /** The FLIP weight: set by check() to 1 (FLIP) or 0 (PIC). */
    double         flip_fraction           = 1.;
    unsigned int   maximum_number_of_steps = 100000000;
    std::string    mass_matrix_text        = "automatic";
    MassMatrixType mass_matrix             = MassMatrixType::lumped;
    /**
     * The consistent fraction alpha of the blended mass matrix: set by
     * check() to 0 with the lumped mass.
     */
    double consistent_mass_fraction = 0.95;

    void
    declare(ParameterHandler &prm);
    void
    check();

    /**
     * The largest step the implicit steps may grow to, on cells of smallest
     * size @p minimum_cell_size h and a largest wave speed @p wave_speed c:
     * Maximum time step if set, else Maximum CFL number times h / c; zero
     * when the steps do not grow (the explicit scheme, fixed steps, or a
     * Maximum CFL number of 0).
     */
    double
    largest_time_step(const double minimum_cell_size,
                      const double wave_speed) const;
  };
} // namespace grainmpm

#endif
