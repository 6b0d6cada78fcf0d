// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_simulator_h
#define grainmpm_simulator_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/postprocess/energy_history.h>
#include <grainmpm/postprocess/grain_history.h>
#include <grainmpm/postprocess/output_writer.h>
#include <grainmpm/time_integration/explicit_leapfrog.h>
#include <grainmpm/time_integration/implicit_theta.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <chrono>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace grainmpm
{
  using namespace dealii;

  /**
   * A grainmpm run: owns the grid, the material points, the materials, the
   * time stepper and the writers; run() reads like the algorithm of
   * DESIGN.md section 2.
   */
  template <int dim>
  class Simulator
  {
  public:
    /**
     * Set up a run from parsed @p parameters. @p prm is the handler they
     * were read with (written to parameters.prm) and @p input_file the
     * file itself (copied to original.prm).
     */
    Simulator(const Parameters<dim>  &parameters,
              const ParameterHandler &prm,
              const std::string      &input_file,
              const MPI_Comm          communicator);

    /** Advance to the end time, writing output on the way. */
    void
    run();

  private:
    /** The time loop of run(). */
    void
    advance_to_end_time();

    /** Time step from the CFL condition or the fixed value. */
    double
    compute_time_step(const double max_speed) const;

    /** Particles, grid, .pvd records, grains.csv and the progress line. */
    void
    write_output(const unsigned int step, const double time, const double dt);

    /**
     * With more than one MPI rank and Load balancing/Steps between
     * repartitioning > 0: repartition the cells weighted by their material
     * points (BackgroundGrid::repartition()).
     */
    void
    balance_load();

    /**
     * Write checkpoint-NNNNNN (Checkpoint subsection): the triangulation
     * with the material points, and the state below.
     */
    void
    write_checkpoint();

    /** Read or write the scalar state of the run with @p archive. */
    template <class Archive>
    void
    serialize_state(Archive &archive);

    const Parameters<dim> &parameters;
    const MPI_Comm         communicator;
    ConditionalOStream     pcout;
    TimerOutput            timer;

    BackgroundGrid<dim>                                  grid;
    Particles::ParticleHandler<dim>                      particle_handler;
    std::vector<std::unique_ptr<ConstitutiveModel<dim>>> materials;
    std::vector<GrainInfo<dim>>                          grains;
    std::unique_ptr<TimeIntegrator<dim>>                 stepper;
    std::unique_ptr<OutputWriter<dim>>                   output_writer;
    std::unique_ptr<EnergyHistory<dim>>                  energy_history;
    std::unique_ptr<GrainHistory<dim>>                   grain_history;

    unsigned int          n_outputs = 0;
    types::particle_index n_removed = 0;
    /** Points the handler lost on this rank (counted, never expected). */
    types::particle_index n_lost          = 0;
    types::particle_index n_held_at_walls = 0;
    EnergySummary<dim>    initial_energy;
    EnergySummary<dim>    current_energy;
    double                minimum_energy = 0.;
    double                maximum_energy = 0.;
    /** Sum of the steps' grid energy changes (StepStatistics). */
    double grid_energy_change = 0.;
    /** The energy ledger since the start. */
    EnergyLedger ledger;
    /** Largest |balance residual| and largest kinetic + elastic energy. */
    double largest_balance         = 0.;
    double largest_kinetic_elastic = 0.;
    /** Largest equivalent plastic strain at the end. */
    double largest_plastic_strain = 0.;
    /** Solver counts of the implicit scheme over the run. */
    struct
    {
      unsigned long newton_iterations     = 0;
      unsigned long linear_iterations     = 0;
      unsigned long residual_evaluations  = 0;
      unsigned long status_changes        = 0;
      unsigned int  max_newton_iterations = 0;
      unsigned int  rejected              = 0;
      double        smallest_step         = std::numeric_limits<double>::max();
    } implicit_totals;
    /** sum_p m_p |v_p| at t = 0, the scale of momentum errors. */
    double initial_momentum_scale = 0.;

    /**
     * Where the time loop starts (0, or a checkpoint): time, desired next
     * step, step number; the next output time, the failure policy's step
     * limit and easy steps, steps with contact, the smallest time step.
     */
    double       start_time        = 0.;
    double       next_step_size    = 0.;
    unsigned int step_offset       = 0;
    double       next_output       = 0.;
    double       step_limit        = 0.;
    unsigned int easy_steps        = 0;
    unsigned int n_contact_steps   = 0;
    double       minimum_time_step = 0.;
    /** Wall-clock time of the last checkpoint, and the ones kept. */
    std::chrono::steady_clock::time_point last_checkpoint;
    std::vector<std::string>              checkpoints;
  };

  /**
   * Read @p filename for dimension @p dim and run it: what `grainmpm FILE`
   * does.
   */
  template <int dim>
  void
  run(const std::string &filename, const MPI_Comm communicator);
} // namespace grainmpm

#endif
