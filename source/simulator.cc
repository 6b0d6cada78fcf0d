// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/stop_signals.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/particles/random_packing.h>
#include <grainmpm/postprocess/input_record.h>
#include <grainmpm/simulator.h>
#include <grainmpm/time_integration/explicit_leapfrog.h>
#include <grainmpm/time_integration/implicit_theta.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  Simulator<dim>::Simulator(const Parameters<dim>  &parameters,
                            const ParameterHandler &prm,
                            const std::string      &input_file,
                            const MPI_Comm          communicator,
                            const bool              quiet)
    : parameters(parameters)
    , communicator(communicator)
    , implicit(parameters.time_stepping.scheme ==
               TimeSteppingScheme::implicit_theta)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , progress(std::cout,
               !quiet && Utilities::MPI::this_mpi_process(communicator) == 0)
    , grid(parameters.grid, communicator)
    , particle_handler(grid.get_triangulation(),
                       grid.get_mapping(),
                       MaterialPointLayout<dim>::n_properties)
    , schedule(parameters.output, parameters.checkpoint, communicator)
    , summary(implicit)
    , timer(pcout,
            parameters.output.test_mode ? TimerOutput::never :
                                          TimerOutput::summary,
            TimerOutput::wall_times)
  {
    try
      {
        record_inputs(parameters, prm, input_file, communicator);
      }
    catch (...)
      {
        timer.disable_output();
        throw;
      }
    for (const auto &material : parameters.materials)
      materials.emplace_back(create_constitutive_model<dim>(
        material, parameters.physics.two_dimensional_model));
  }



  template <int dim>
  void
  Simulator<dim>::run()
  {
    // On an error, end without the timing table (TimerOutput would warn
    // that it cannot synchronise while an exception is in flight).
    bool stepping = false;
    try
      {
        setup();
        stepping = true;
        const StopSignals stop_signals;
        DiscreteTime      time(start_time,
                          parameters.time_stepping.end_time,
                          next_step_size);
        const auto        step_number = [&]() {
          return step_offset + time.get_step_number();
        };
        wall_clock.restart();
        while (!time.is_at_end() &&
               step_number() < parameters.time_stepping.maximum_number_of_steps)
          {
            const StepStatistics statistics = advance_one_step(time);
            time.advance_time();
            record_step(step_number(), time, statistics);
            if (schedule.output_due(time.get_current_time(), time.is_at_end()))
              write_output(
                step_number(),
                time.get_current_time(),
                time.get_previous_step_size(),
                schedule.output_written(time.get_current_time(),
                                        time.get_previous_step_size()));
            // Grown steps are bounded by the motion of the grains, not by
            // the vibration of their points.
            if (!time.is_at_end())
              time.set_desired_next_step_size(time_step_controller->next_step(
                statistics.events.max_speed,
                time_step_controller->needs_grain_speed() ?
                  postprocessor->largest_grain_speed(particle_handler) :
                  -1.));
            repartition_and_checkpoint(step_number(), time);
            if (const int signal =
                  time.is_at_end() ? 0 : stop_signals.received(communicator))
              stop(signal, step_number(), time);
          }
        print_summary(step_number(), time.get_current_time());
      }
    catch (const InputError &error)
      {
        // Say what is left of an interrupted run.
        timer.disable_output();
        if (!stepping)
          throw;
        std::ostringstream message;
        message << error.what() << " The output up to t = " << last_output_time
                << " is complete in " << parameters.output.directory << ".";
        throw InputError("", message.str());
      }
    catch (...)
      {
        timer.disable_output();
        throw;
      }
  }



  template <int dim>
  void
  Simulator<dim>::setup()
  {
    // A resumed run reads its state first: the histories continue from the
    // lengths they had at the checkpoint.
    checkpoints =
      std::make_unique<CheckpointManager<dim>>(parameters.checkpoint,
                                               parameters.output.directory,
                                               communicator);
    typename Postprocessor<dim>::HistoryLengths lengths;
    typename CheckpointManager<dim>::MassChange mass_change;
    if (checkpoints->resuming())
      checkpoints->read_state([&](boost::archive::binary_iarchive &archive) {
        archive >> lengths.energy >> lengths.grains >> lengths.walls >>
          lengths.contacts;
      });
    // Resumed in another output directory: the histories start as those of
    // the checkpoint's run up to the checkpoint.
    const std::string resume_source = checkpoints->resume_source();
    if (!resume_source.empty())
      Postprocessor<dim>::copy_histories(resume_source,
                                         parameters.output.directory,
                                         lengths,
                                         communicator);

    {
      TimerOutput::Scope  scope(timer, "setup");
      GrainGenerator<dim> generator(parameters);
      grains = generator.generate(grid, particle_handler);
      if (checkpoints->resuming())
        {
          checkpoints->load(CheckpointManager<dim>::fingerprint(parameters,
                                                                grains),
                            grid,
                            particle_handler);
          // Another Mass scaling than the checkpoint's: the points' masses
          // follow it (before anything measures them), and the ledger's
          // reference moves with the kinetic energy and momentum that
          // changes (below, once the ledger is read).
          mass_change = CheckpointManager<dim>::rescale_masses(parameters,
                                                               grains,
                                                               particle_handler,
                                                               communicator);
        }

      if (implicit)
        // (The progress stream is active unless --quiet, on rank 0.)
        stepper = std::make_unique<ImplicitTheta<dim>>(
          parameters, grid, grains, materials, !progress.is_active());
      else
        stepper = std::make_unique<ExplicitLeapfrog<dim>>(parameters,
                                                          grid,
                                                          grains,
                                                          materials);
      if (implicit && parameters.time_stepping.adaptive_time_stepping &&
          parameters.time_stepping.explicit_fallback)
        fallback = std::make_unique<ExplicitFallback<dim>>(parameters,
                                                           grid,
                                                           grains,
                                                           materials);
      last_stepper         = stepper.get();
      time_step_controller = std::make_unique<TimeStepController>(
        parameters.time_stepping,
        parameters.nonlinear_solver.max_iterations,
        grid.minimum_cell_size(),
        largest_wave_speed(grains, materials));
      postprocessor = std::make_unique<Postprocessor<dim>>(parameters,
                                                           grid,
                                                           grains,
                                                           materials,
                                                           particle_handler,
                                                           lengths,
                                                           communicator);
    }
    if (checkpoints->resuming())
      {
        checkpoints->read_state(
          [this](boost::archive::binary_iarchive &archive) {
            archive >> *this;
            postprocessor->serialize(archive, 0);
          });
        if (!resume_source.empty())
          postprocessor->prefix_output_records(
            std::filesystem::relative(resume_source,
                                      parameters.output.directory)
              .string());
        checkpoints->finish_resume();
        summary.shift_reference(mass_change.kinetic, mass_change.momentum);
      }
    // The grains fill only part of the box: balance the material points.
    // A checkpoint is written right after a repartition, so a resumed run
    // has the partition of the uninterrupted one (and its bits) when it
    // runs on as many ranks.
    balance_load();
    print_header();

    // Particles that the handler loses (should not happen: G2P checks the
    // box first) are counted, never silently dropped.
    particle_handler.signals.particle_lost.connect(
      [this](const auto &, const auto &) { ++n_lost; });

    if (!parameters.checkpoint.resume_from.empty())
      {
        pcout << "resumed from " << parameters.checkpoint.resume_from
              << " at step " << step_offset << ", t = " << start_time
              << std::endl;
        if (mass_change.factor != 1.)
          pcout << "the checkpoint's point masses multiplied by "
                << mass_change.factor
                << " (Mass scaling = " << parameters.time_stepping.mass_scaling
                << "), their velocities "
                << (parameters.checkpoint.scale_velocities_with_mass ?
                      "divided by its square root (Checkpoint/Scale "
                      "velocities with the mass)" :
                      "kept")
                << "; the kinetic energy changed by " << mass_change.kinetic
                << ", which moves the ledger's reference" << std::endl;
      }
    else
      start_new_run();
  }



  template <int dim>
  void
  Simulator<dim>::print_header()
  {
    if (!parameters.output.test_mode)
      progress << "grainmpm " << GRAINMPM_VERSION << " on deal.II "
               << DEAL_II_PACKAGE_VERSION << ", " << dim << "D, "
               << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank"
               << (Utilities::MPI::n_mpi_processes(communicator) > 1 ? "s" : "")
               << std::endl;
    progress << "grainmpm: " << dim << "D, "
             << grid.get_triangulation().n_global_active_cells() << " cells, "
             << grains.size() << " grains, "
             << particle_handler.n_global_particles() << " material points"
             << std::endl;
    if (parameters.time_stepping.mass_scaling != 1.)
      progress << "mass scaling " << parameters.time_stepping.mass_scaling
               << ": densities multiplied and gravity divided by it; the "
                  "masses, momenta and kinetic energies written are those "
                  "of the scaled densities"
               << std::endl;
  }



  template <int dim>
  void
  Simulator<dim>::start_new_run()
  {
    // The initial energies, the momentum scale sum_p m_p |v_p|, the first
    // output and the first step.
    double max_speed = 0., momentum_scale = 0.;
    for (const auto &particle : particle_handler)
      {
        const auto   properties = particle.get_properties();
        const double speed =
          MaterialPointLayout<dim>::get_velocity(properties).norm();
        max_speed = std::max(max_speed, speed);
        if (!grains[MaterialPointLayout<dim>::get_grain(properties)].rigid)
          momentum_scale += properties[MaterialPointLayout<dim>::mass] * speed;
      }
    momentum_scale = Utilities::MPI::sum(momentum_scale, communicator);
    max_speed      = Utilities::MPI::max(max_speed, communicator);

    const EnergySummary<dim> initial =
      postprocessor->compute_energies(particle_handler, StepStatistics());
    summary.start(initial, momentum_scale);
    postprocessor->write_initial_row(initial, summary.get_ledger());
    write_output(0, 0., 0., schedule.extra_output_written());
    start_time     = 0.;
    next_step_size = time_step_controller->first_step(max_speed);
  }



  template <int dim>
  void
  Simulator<dim>::record_step(const unsigned int    step,
                              const DiscreteTime   &time,
                              const StepStatistics &statistics)
  {
    summary.add_step(statistics);
    if (statistics.events.n_removed > 0)
      pcout << "  " << statistics.events.n_removed
            << " particles left through open faces at t = "
            << time.get_current_time() << std::endl;

    TimerOutput::Scope       scope(timer, "diagnostics");
    const EnergySummary<dim> current =
      postprocessor->compute_energies(particle_handler, statistics);
    postprocessor->write_step(step,
                              time.get_current_time(),
                              time.get_previous_step_size(),
                              statistics,
                              last_stepper->get_impulses(),
                              current,
                              summary.get_ledger(),
                              summary.get_initial_energies(),
                              particle_handler);
    summary.add_energies(current);
    // Energy created by the implicit steps (the balance residual above a
    // tenth of the energy reference, or of the boundary work if that is
    // larger) is said once, with the levers.
    const double created = summary.created_energy_fraction();
    if (implicit && !creation_noted && created > 0.1)
      {
        creation_noted = true;
        pcout << "  note: at t = " << time.get_current_time()
              << " the implicit steps have created energy: the balance "
                 "residual is +"
              << created
              << " of the energy reference (or of the boundary work, if "
                 "larger). A loose Nonlinear "
                 "solver/Tolerance leaves errors that work like forces, and "
                 "at Time stepping/Theta = 0.5 (here "
              << parameters.time_stepping.theta
              << ") long steps through contact can feed the fastest modes "
                 "of a packing until it blows up. A tighter Tolerance, "
                 "Theta = 0.6 (which damps those modes) or a smaller Time "
                 "step helps (doc/theory.md, section 9.6)."
              << std::endl;
      }
    if (!std::isfinite(current.total()))
      throw InputError("Time stepping",
                       "the solution became NaN/infinite at t = " +
                         std::to_string(time.get_current_time()) +
                         ": the time step is too large for this problem "
                         "(lower CFL number or Time step).");
  }



  template <int dim>
  void
  Simulator<dim>::write_output(const unsigned int step,
                               const double       time,
                               const double       dt,
                               const unsigned int index)
  {
    TimerOutput::Scope scope(timer, "output");
    last_output_step = step;
    last_output_time = time;
    postprocessor->write_output(
      step, time, index, particle_handler, *last_stepper);

    // The progress line; the wall time and the estimate of the time to
    // the end (from the pace since the loop started) are not in test mode.
    // Formatted in a stream of its own: the progress line's precision must
    // not stay on std::cout, where the summary and messages follow.
    const EnergySummary<dim> &energies = summary.get_current_energies();
    std::ostringstream        line;
    line << "step " << std::setw(6) << step << "  t = " << std::scientific
         << std::setprecision(4) << time << "  dt = " << std::setprecision(3)
         << dt << "  E_kin = " << std::setprecision(5) << energies.kinetic
         << "  E_el = " << energies.elastic << "  E_tot = " << energies.total();
    if (!parameters.output.test_mode && time > start_time)
      {
        const double elapsed = wall_clock.wall_time();
        const double left    = elapsed *
                            (parameters.time_stepping.end_time - time) /
                            (time - start_time);
        line << std::fixed << std::setprecision(1) << "  wall " << elapsed
             << " s  to end ~" << left << " s";
      }
    progress << line.str() << std::endl;
  }



  template <int dim>
  void
  Simulator<dim>::balance_load()
  {
    if (Utilities::MPI::n_mpi_processes(communicator) == 1 ||
        parameters.load_balancing.steps_between == 0)
      return;
    TimerOutput::Scope scope(timer, "load balancing");
    grid.repartition(particle_handler,
                     parameters.load_balancing.particle_weight);
  }



  template <int dim>
  void
  Simulator<dim>::print_summary(const unsigned int n_steps, const double time)
  {
    double largest_plastic_strain = 0.;
    for (const auto &particle : particle_handler)
      largest_plastic_strain = std::max(
        largest_plastic_strain,
        particle.get_properties()[MaterialPointLayout<dim>::plastic_strain]);
    largest_plastic_strain =
      Utilities::MPI::max(largest_plastic_strain, communicator);
    const types::particle_index n_lost_total =
      Utilities::MPI::sum(n_lost, communicator);
    const types::particle_index n_points =
      particle_handler.n_global_particles();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      summary.print(std::cout,
                    n_steps,
                    time,
                    n_lost_total,
                    n_points,
                    largest_plastic_strain,
                    time_step_controller->smallest_step_tried());

    std::vector<SummaryRow> rows =
      summary.rows(n_steps,
                   time,
                   n_lost_total,
                   n_points,
                   largest_plastic_strain,
                   time_step_controller->smallest_step_tried());

    // Peak resident memory and wall times (machine-dependent, so not in
    // test mode).
    if (!parameters.output.test_mode)
      {
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double peak     = memory.VmHWM / 1024.; // MiB
        const double peak_sum = Utilities::MPI::sum(peak, communicator);
        const double peak_max = Utilities::MPI::max(peak, communicator);
        pcout << "  peak memory: " << peak_sum << " MiB summed over "
              << Utilities::MPI::n_mpi_processes(communicator)
              << " ranks, largest rank " << peak_max << " MiB" << std::endl;
        append_measured_rows(
          rows, wall_clock.wall_time(), timer, peak_sum, peak_max);
      }
    write_summary_file(parameters.output.directory + "/summary.csv",
                       rows,
                       communicator);
  }



  template <int dim>
  void
  run(const std::string &filename,
      const MPI_Comm     communicator,
      const bool         quiet)
  {
    ParameterHandler prm;
    Parameters<dim>  parameters;
    parameters.parse(filename, prm);
    add_random_packing(parameters);
    parameters.apply_mass_scaling();
    Simulator<dim> simulator(parameters, prm, filename, communicator, quiet);
    simulator.run();
  }



  template class Simulator<2>;
  template class Simulator<3>;
  template void
  run<2>(const std::string &, const MPI_Comm, const bool);
  template void
  run<3>(const std::string &, const MPI_Comm, const bool);
} // namespace grainmpm
