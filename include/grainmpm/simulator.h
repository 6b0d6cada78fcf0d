// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_simulator_h
#define grainmpm_simulator_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/postprocess/checkpoint_manager.h>
#include <grainmpm/postprocess/output_schedule.h>
#include <grainmpm/postprocess/postprocessor.h>
#include <grainmpm/postprocess/run_summary.h>
#include <grainmpm/time_integration/explicit_fallback.h>
#include <grainmpm/time_integration/time_integrator.h>
#include <grainmpm/time_integration/time_step_controller.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/discrete_time.h>
#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/serialization/access.hpp>
#include <boost/serialization/version.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Thrown by Simulator::run() when the run stopped early on SIGTERM or
   * SIGINT after writing its output and, if checkpointing is on, a
   * checkpoint. `main()` prints the message and returns 128 + the signal
   * number, the exit status of a process killed by it.
   */
  class RunStopped : public std::runtime_error
  {
  public:
    RunStopped(const int signal, const std::string &message)
      : std::runtime_error(message)
      , signal(signal)
    {}

    /** The signal that stopped the run. */
    const int signal;
  };



  /**
   * A grainmpm run: owns the grid, the material points, the materials, the
   * time integrator and the objects around the time loop (time step
   * controller, output and checkpoint schedule, checkpoints, writers, run
   * summary); run() reads like the algorithm.
   */
  template <int dim>
  class Simulator
  {
  public:
    /**
     * Set up a run from parsed @p parameters. @p prm is the handler they
     * were read with (written to parameters.prm) and @p input_file the
     * file itself (copied to original.prm). With @p quiet, no header and
     * no progress lines: only the summary, warnings and errors.
     */
    Simulator(const Parameters<dim>  &parameters,
              const ParameterHandler &prm,
              const std::string      &input_file,
              const MPI_Comm          communicator,
              const bool              quiet = false);

    /** Advance to the end time, writing output on the way. */
    void
    run();

  private:
    /**
     * Grains and material points (or those of the checkpoint the run
     * resumes from), the time integrator, the writers; the first output
     * of a new run. Sets where the time loop starts.
     */
    void
    setup();

    /**
     * The header (versions, dimension, ranks; not in test mode) and the
     * line with the numbers of cells, grains and material points, unless
     * quiet.
     */
    void
    print_header();

    /**
     * A run that does not resume: the initial energies and the momentum
     * scale into the summary, the first row of energy.csv, the output at
     * t = 0 and the first time step.
     */
    void
    start_new_run();

    /**
     * One step from the current time of @p time, retried with smaller
     * steps as the failure policy allows; throws InputError (after writing
     * output) when it allows no more.
     */
    StepStatistics
    advance_one_step(DiscreteTime &time);

    /**
     * Advance the step of @p time that the implicit solve could not take,
     * after @p rejected attempts, by explicit sub-steps (ExplicitFallback).
     */
    StepStatistics
    advance_explicitly(const DiscreteTime &time, const unsigned int rejected);

    /**
     * The energies after step @p step (the time of @p time) and the
     * histories; @p statistics of the step into the run summary.
     */
    void
    record_step(const unsigned int    step,
                const DiscreteTime   &time,
                const StepStatistics &statistics);

    /**
     * Particles, grid, grains.csv, contacts.csv and the force chains, and
     * the progress line.
     */
    void
    write_output(const unsigned int step,
                 const double       time,
                 const double       dt,
                 const unsigned int index);

    /**
     * Repartition at `Steps between repartitioning` and before a
     * checkpoint, and write the checkpoints the schedule asks for, after
     * step @p step.
     */
    void
    repartition_and_checkpoint(const unsigned int  step,
                               const DiscreteTime &time);

    /** Write the checkpoint of the state after step @p step. */
    void
    write_checkpoint(const unsigned int step, const DiscreteTime &time);

    /**
     * Stop after step @p step on the signal @p signal: write the output
     * and a checkpoint of this step (if checkpointing is on) unless they
     * were just written, print the summary and how to resume, and throw
     * RunStopped.
     */
    [[noreturn]] void
    stop(const int signal, const unsigned int step, const DiscreteTime &time);

    /**
     * With more than one MPI rank and Load balancing/Steps between
     * repartitioning > 0: repartition the cells weighted by their material
     * points (BackgroundGrid::repartition()).
     */
    void
    balance_load();

    /** The final summary after @p n_steps steps to @p time. */
    void
    print_summary(const unsigned int n_steps, const double time);

    /**
     * Read or write the state of the run with @p archive: where the time
     * loop starts, the time step controller, the schedule and the summary.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version);

    friend class boost::serialization::access;

    const Parameters<dim> &parameters;
    const MPI_Comm         communicator;
    const bool             implicit;
    ConditionalOStream     pcout;
    /** The header and the progress lines (not with --quiet). */
    ConditionalOStream progress;
    /** Wall clock at the start of the time loop, for the progress lines. */
    Timer wall_clock;

    BackgroundGrid<dim>                                  grid;
    Particles::ParticleHandler<dim>                      particle_handler;
    std::vector<std::unique_ptr<ConstitutiveModel<dim>>> materials;
    std::vector<GrainInfo<dim>>                          grains;
    std::unique_ptr<TimeIntegrator<dim>>                 stepper;
    /** Implicit runs with `Explicit fallback`: the explicit sub-steps. */
    std::unique_ptr<ExplicitFallback<dim>> fallback;
    /**
     * Whether the run has said that its implicit steps created energy
     * (record_step()); said once.
     */
    bool creation_noted = false;
    /** The integrator of the last step: its grid and impulses are output. */
    const TimeIntegrator<dim>              *last_stepper = nullptr;
    std::unique_ptr<TimeStepController>     time_step_controller;
    OutputSchedule                          schedule;
    std::unique_ptr<CheckpointManager<dim>> checkpoints;
    std::unique_ptr<Postprocessor<dim>>     postprocessor;
    RunSummary<dim>                         summary;
    /**
     * The timing table, printed when the run ends. Made after the members
     * whose construction can fail, and silenced when anything fails before
     * the time loop: an error found before the first step prints no empty
     * table before its message.
     */
    TimerOutput timer;

    /** The steps after which output and a checkpoint were last written. */
    unsigned int last_output_step     = numbers::invalid_unsigned_int;
    double       last_output_time     = 0.;
    unsigned int last_checkpoint_step = numbers::invalid_unsigned_int;

    /** Points the handler lost on this rank (counted, never expected). */
    types::particle_index n_lost = 0;

    /**
     * Where the time loop starts (0, or a checkpoint): time, desired next
     * step, step number.
     */
    double       start_time     = 0.;
    double       next_step_size = 0.;
    unsigned int step_offset    = 0;
  };

  /**
   * Read @p filename for dimension @p dim and run it: what `grainmpm FILE`
   * does (`grainmpm --quiet FILE` with @p quiet).
   */
  template <int dim>
  void
  run(const std::string &filename,
      const MPI_Comm     communicator,
      const bool         quiet = false);
} // namespace grainmpm

namespace boost::serialization
{
  /**
   * The version of the state a checkpoint keeps of a run: 1 adds the
   * contact status the implicit scheme starts its next step from
   * (HeldContactStatus), 2 the length of the last step of the implicit
   * scheme's error estimate (StepErrorEstimator), 3 whether its last
   * step was quasi-static (Quasi-static theta), 4 where the contact
   * locates the rigid grains (RigidGrainMotion). Checkpoints before
   * version 2 hold material points with fewer properties, and
   * CheckpointManager::load() refuses them.
   */
  template <int dim>
  struct version<grainmpm::Simulator<dim>>
  {
    using type                 = mpl::int_<4>;
    using tag                  = mpl::integral_c_tag;
    static constexpr int value = type::value;
  };
} // namespace boost::serialization

#endif
