// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/grain_list.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/particles/random_packing.h>
#include <grainmpm/simulator.h>

#include <deal.II/base/discrete_time.h>
#include <deal.II/base/utilities.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  Simulator<dim>::Simulator(const Parameters<dim>  &parameters,
                            const ParameterHandler &prm,
                            const std::string      &input_file,
                            const MPI_Comm          communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(pcout,
            parameters.output.test_mode ? TimerOutput::never :
                                          TimerOutput::summary,
            TimerOutput::wall_times)
    , grid(parameters.grid, communicator)
    , particle_handler(grid.get_triangulation(),
                       grid.get_mapping(),
                       MaterialPointLayout<dim>::n_properties)
  {
    // Record the inputs before anything can fail (DESIGN.md section 6).
    const std::string &directory = parameters.output.directory;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::filesystem::create_directories(directory);
        std::filesystem::copy_file(
          input_file,
          directory + "/original.prm",
          std::filesystem::copy_options::overwrite_existing);
        std::ofstream used(directory + "/parameters.prm");
        prm.print_parameters(used, ParameterHandler::PRM);
        if (parameters.n_packed_grains > 0)
          {
            // The generated grains, to be read back as a Grain list file.
            std::ofstream packing(directory + "/packing.csv");
            write_grain_list<dim>(
              packing,
              std::vector<GrainParameters<dim>>(parameters.grains.end() -
                                                  parameters.n_packed_grains,
                                                parameters.grains.end()));
          }
      }

    for (const auto &material : parameters.materials)
      materials.emplace_back(create_constitutive_model<dim>(
        material, parameters.physics.two_dimensional_model));
  }



  template <int dim>
  double
  Simulator<dim>::compute_time_step(const double max_speed) const
  {
    if (parameters.time_stepping.time_step > 0.)
      return parameters.time_stepping.time_step;
    return parameters.time_stepping.cfl_number * grid.minimum_cell_size() /
           (largest_wave_speed(grains, materials) + max_speed);
  }



  template <int dim>
  void
  Simulator<dim>::write_output(const unsigned int step,
                               const double       time,
                               const double       dt)
  {
    TimerOutput::Scope scope(timer, "output");
    if (parameters.output.write_particles)
      output_writer->write_particles(particle_handler, time, n_outputs);
    if (parameters.output.write_grid && step > 0)
      output_writer->write_grid(*stepper, time, n_outputs);
    if (parameters.output.write_grain_history)
      grain_history->write(particle_handler, time);
    ++n_outputs;

    pcout << "step " << std::setw(6) << step << "  t = " << std::scientific
          << std::setprecision(4) << time << "  dt = " << std::setprecision(3)
          << dt << "  E_kin = " << std::setprecision(5)
          << current_energy.kinetic << "  E_el = " << current_energy.elastic
          << "  E_tot = " << current_energy.total() << std::defaultfloat
          << std::endl;
  }



  template <int dim>
  void
  Simulator<dim>::advance_to_end_time()
  {
    // A resumed run reads its state first: the histories continue from the
    // lengths they had at the checkpoint.
    const std::string &resume        = parameters.checkpoint.resume_from;
    std::uintmax_t     energy_length = 0, grains_length = 0;
    std::ifstream      resume_stream;
    std::unique_ptr<boost::archive::binary_iarchive> resume_archive;
    if (!resume.empty())
      {
        resume_stream.open(resume + "/state", std::ios::binary);
        if (!resume_stream)
          throw InputError("Checkpoint/Resume from = " + resume,
                           "there is no checkpoint (file state) in this "
                           "directory.");
        resume_archive =
          std::make_unique<boost::archive::binary_iarchive>(resume_stream);
        *resume_archive >> energy_length >> grains_length;
      }

    {
      TimerOutput::Scope  scope(timer, "setup");
      GrainGenerator<dim> generator(parameters);
      grains = generator.generate(grid, particle_handler);
      if (!resume.empty())
        {
          // The material points of the checkpoint replace the new ones,
          // before anything else looks at the grid.
          particle_handler.clear();
          grid.load(resume + "/grid");
          particle_handler.deserialize();
        }

      if (parameters.time_stepping.scheme == TimeSteppingScheme::implicit_theta)
        stepper = std::make_unique<ImplicitTheta<dim>>(parameters,
                                                       grid,
                                                       grains,
                                                       materials);
      else
        stepper = std::make_unique<ExplicitLeapfrog<dim>>(parameters,
                                                          grid,
                                                          grains,
                                                          materials);
      // Photoelastic fringe order per unit principal stress difference,
      // per grain: thickness / material fringe value.
      std::vector<double> fringe_factors;
      for (const auto &grain : grains)
        {
          const MaterialParameters &material =
            parameters.materials[grain.material];
          fringe_factors.push_back(material.material_fringe_value > 0. ?
                                     material.thickness /
                                       material.material_fringe_value :
                                     0.);
        }
      output_writer = std::make_unique<OutputWriter<dim>>(parameters.output,
                                                          grid,
                                                          fringe_factors);
      energy_history =
        std::make_unique<EnergyHistory<dim>>(parameters.output.directory +
                                               "/energy.csv",
                                             grains,
                                             materials,
                                             parameters.physics.gravity,
                                             communicator,
                                             energy_length);
      grain_history =
        std::make_unique<GrainHistory<dim>>(parameters.output.directory +
                                              "/grains.csv",
                                            grains.size(),
                                            communicator,
                                            grains_length);
    }
    if (resume_archive != nullptr)
      {
        serialize_state(*resume_archive);
        *resume_archive >> *energy_history >> *output_writer;
      }
    // The grains fill only part of the box: balance the material points.
    // A checkpoint is written right after a repartition, so a resumed run
    // has the partition of the uninterrupted one (and its bits) when it
    // runs on as many ranks.
    balance_load();
    pcout << "grainmpm: " << dim << "D, "
          << grid.get_triangulation().n_global_active_cells() << " cells, "
          << grains.size() << " grains, "
          << particle_handler.n_global_particles() << " material points"
          << std::endl;

    // Particles that the handler loses (should not happen: G2P checks the
    // box first) are counted, never silently dropped.
    particle_handler.signals.particle_lost.connect(
      [this](const auto &, const auto &) { ++n_lost; });

    double max_speed = 0.;
    for (const auto &particle : particle_handler)
      {
        const auto   properties = particle.get_properties();
        const double speed =
          MaterialPointLayout<dim>::get_velocity(properties).norm();
        max_speed = std::max(max_speed, speed);
        if (!grains[MaterialPointLayout<dim>::get_grain(properties)].rigid)
          initial_momentum_scale +=
            properties[MaterialPointLayout<dim>::mass] * speed;
      }
    initial_momentum_scale =
      Utilities::MPI::sum(initial_momentum_scale, communicator);
    max_speed = Utilities::MPI::max(max_speed, communicator);

    const double end_time        = parameters.time_stepping.end_time;
    const double output_interval = parameters.output.interval;
    const bool   implicit =
      parameters.time_stepping.scheme == TimeSteppingScheme::implicit_theta;
    if (resume.empty())
      {
        initial_energy = current_energy =
          energy_history->compute(particle_handler);
        minimum_energy = maximum_energy = initial_energy.total();
        largest_kinetic_elastic =
          initial_energy.kinetic + initial_energy.elastic;
        energy_history->write_row(
          0, 0., 0., initial_energy, StepStatistics(), ledger, initial_energy);
        write_output(0, 0., 0.);
        next_output       = output_interval;
        start_time        = 0.;
        next_step_size    = compute_time_step(max_speed);
        minimum_time_step = parameters.time_stepping.minimum_time_step > 0. ?
                              parameters.time_stepping.minimum_time_step :
                              next_step_size / 1024.;
      }
    else
      pcout << "resumed from " << resume << " at step " << step_offset
            << ", t = " << start_time << std::endl;
    DiscreteTime time(start_time, end_time, next_step_size);
    last_checkpoint = std::chrono::steady_clock::now();
    // Checkpoints already in the output directory count towards the ones
    // kept (a resumed run continues the list of the run it resumes).
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        for (const auto &entry :
             std::filesystem::directory_iterator(parameters.output.directory))
          {
            const std::string name = entry.path().filename().string();
            if (entry.is_directory() && name.rfind("checkpoint-", 0) == 0 &&
                name.find(".tmp") == std::string::npos)
              checkpoints.push_back(entry.path().string());
          }
        std::sort(checkpoints.begin(), checkpoints.end());
      }
    // The step number of the whole run (a resumed DiscreteTime counts from
    // the checkpoint).
    const auto step_number = [&time, this]() {
      return step_offset + time.get_step_number();
    };
    while (!time.is_at_end() &&
           step_number() < parameters.time_stepping.maximum_number_of_steps)
      {
        StepStatistics statistics;
        unsigned int   rejected_attempts = 0;
        for (;;)
          {
            {
              TimerOutput::Scope scope(timer,
                                       implicit ? "implicit step" :
                                                  "explicit step");
              statistics = stepper->advance(particle_handler,
                                            time.get_current_time(),
                                            time.get_next_step_size());
            }
            implicit_totals.residual_evaluations +=
              statistics.residual_evaluations;
            if (statistics.converged)
              break;

            // Rejected: the particles are untouched; halve dt and retry.
            ++rejected_attempts;
            ++implicit_totals.rejected;
            const double failed_step = time.get_next_step_size();
            pcout << "  step " << step_number() + 1
                  << " at t = " << time.get_current_time()
                  << " rejected with dt = " << failed_step << ": "
                  << statistics.failure << std::endl;
            if (!parameters.time_stepping.adaptive_time_stepping ||
                0.5 * failed_step < minimum_time_step)
              {
                write_output(step_number(),
                             time.get_current_time(),
                             time.get_previous_step_size());
                std::ostringstream message;
                message
                  << "the implicit step from t = " << time.get_current_time()
                  << " failed with dt = " << failed_step << " ("
                  << statistics.failure << ") and "
                  << (parameters.time_stepping.adaptive_time_stepping ?
                        "halving it would go below the minimum time step " +
                          std::to_string(minimum_time_step) :
                        std::string("adaptive time stepping is off"))
                  << ". Lower Time stepping/CFL number or Time step, or "
                     "raise Nonlinear solver/Maximum Newton iterations. "
                     "Output up to t = "
                  << time.get_current_time() << " is complete in "
                  << parameters.output.directory << ".";
                throw InputError(
                  parameters.time_stepping.adaptive_time_stepping ?
                    "Time stepping/Minimum time step" :
                    "Time stepping/Adaptive time stepping",
                  message.str());
              }
            step_limit = 0.5 * failed_step;
            easy_steps = 0;
            implicit_totals.smallest_step =
              std::min(implicit_totals.smallest_step, step_limit);
            time.set_desired_next_step_size(step_limit);
          }
        statistics.rejected = rejected_attempts;
        if (implicit)
          {
            implicit_totals.newton_iterations += statistics.newton_iterations;
            implicit_totals.linear_iterations += statistics.linear_iterations;
            implicit_totals.status_changes += statistics.status_changes;
            implicit_totals.max_newton_iterations =
              std::max(implicit_totals.max_newton_iterations,
                       statistics.newton_iterations);
            // Grow a cut step back after easy steps.
            if (step_limit > 0. && 2 * statistics.newton_iterations <=
                                     parameters.nonlinear_solver.max_iterations)
              if (++easy_steps >= parameters.time_stepping.steps_before_growth)
                {
                  step_limit *= 2.;
                  easy_steps = 0;
                }
          }
        time.advance_time();
        grid_energy_change += statistics.grid_energy_change;
        ledger.add(statistics);
        n_removed += statistics.n_removed;
        n_held_at_walls += statistics.n_held_at_walls;
        if (statistics.n_contact_nodes > 0)
          ++n_contact_steps;
        if (statistics.n_removed > 0)
          pcout << "  " << statistics.n_removed
                << " particles left through open faces at t = "
                << time.get_current_time() << std::endl;

        {
          TimerOutput::Scope scope(timer, "diagnostics");
          current_energy = energy_history->compute(particle_handler);
          energy_history->write_row(step_number(),
                                    time.get_current_time(),
                                    time.get_previous_step_size(),
                                    current_energy,
                                    statistics,
                                    ledger,
                                    initial_energy);
          minimum_energy = std::min(minimum_energy, current_energy.total());
          maximum_energy = std::max(maximum_energy, current_energy.total());
          largest_kinetic_elastic =
            std::max(largest_kinetic_elastic,
                     current_energy.kinetic + current_energy.elastic);
          largest_balance =
            std::max(largest_balance,
                     std::abs(ledger.balance(current_energy, initial_energy)));
        }
        if (!std::isfinite(current_energy.total()))
          throw InputError("Time stepping",
                           "the solution became NaN/infinite at t = " +
                             std::to_string(time.get_current_time()) +
                             ": the time step is too large for this problem "
                             "(lower CFL number or Time step).");

        if (time.get_current_time() >= next_output * (1. - 1e-12) ||
            time.is_at_end())
          {
            write_output(step_number(),
                         time.get_current_time(),
                         time.get_previous_step_size());
            while (next_output <= time.get_current_time() * (1. + 1e-12))
              next_output +=
                (output_interval > 0. ? output_interval :
                                        time.get_previous_step_size());
          }
        if (!time.is_at_end())
          {
            double next_step = compute_time_step(statistics.max_speed);
            if (step_limit > 0. && step_limit < next_step)
              next_step = step_limit;
            else
              step_limit = 0.;
            time.set_desired_next_step_size(next_step);
          }

        // Repartition after the output (the grid output reads the slot
        // layout of the step), at the interval and before a checkpoint:
        // a resumed run repartitions first, by the same weights.
        const auto        &checkpoint = parameters.checkpoint;
        const unsigned int balance_interval =
          parameters.load_balancing.steps_between;
        // (The ranks' clocks differ: rank 0 decides.)
        const bool checkpoint_now =
          !time.is_at_end() &&
          ((checkpoint.steps_between > 0 &&
            step_number() % checkpoint.steps_between == 0) ||
           (checkpoint.minutes_between > 0. &&
            Utilities::MPI::broadcast(
              communicator,
              std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            last_checkpoint)
                  .count() >= 60. * checkpoint.minutes_between)));
        if (!time.is_at_end() &&
            (checkpoint_now ||
             (balance_interval > 0 && step_number() % balance_interval == 0)))
          balance_load();

        // Checkpoint by steps or wall-clock time.
        if (checkpoint_now)
          {
            TimerOutput::Scope scope(timer, "checkpoint");
            // The state is that of a run starting here.
            const unsigned int offset = step_offset;
            start_time                = time.get_current_time();
            next_step_size            = time.get_next_step_size();
            step_offset               = step_number();
            write_checkpoint();
            step_offset     = offset;
            last_checkpoint = std::chrono::steady_clock::now();
          }
      }

    // Final summary: O(1) numbers, fit for the regression tests. Energies
    // are relative to the initial total energy, or to the largest one if
    // the run starts at rest.
    const bool        starts_at_rest = !(initial_energy.total() > 0.);
    const double      reference      = starts_at_rest ?
                                         std::max(largest_kinetic_elastic, 1e-300) :
                                         initial_energy.total();
    const std::string scale          = starts_at_rest ? "E_max" : "E_total(0)";
    for (const auto &particle : particle_handler)
      largest_plastic_strain = std::max(
        largest_plastic_strain,
        particle.get_properties()[MaterialPointLayout<dim>::plastic_strain]);
    largest_plastic_strain =
      Utilities::MPI::max(largest_plastic_strain, communicator);
    pcout << "\nfinished: " << step_number()
          << " steps to t = " << time.get_current_time() << "\n"
          << "  steps with contact:       " << n_contact_steps << "\n"
          << "  particles removed:        "
          << n_removed + Utilities::MPI::sum(n_lost, communicator) << "\n"
          << "  material points left:     "
          << particle_handler.n_global_particles() << "\n";
    if (n_held_at_walls > 0)
      pcout << "  points held at walls:     " << n_held_at_walls
            << " times (carried less than half a cell through a closed "
               "face)\n";
    pcout << "  E_total(end) / " << scale << " = "
          << current_energy.total() / reference << "\n"
          << "  min, max E_total / " << scale << " = "
          << minimum_energy / reference << ", " << maximum_energy / reference
          << "\n"
          << "  E_kin(end) / " << scale << " = "
          << current_energy.kinetic / reference << "\n"
          << "  E_el(end) / " << scale << " = "
          << current_energy.elastic / reference << "\n"
          << "  energy ledger / " << scale
          << ": plastic work = " << ledger.plastic_work / reference
          << ", friction work = " << ledger.friction_work / reference
          << ", boundary work = " << ledger.boundary_work / reference
          << ", transfers = " << ledger.transfer / reference
          << ", balance residual = "
          << ledger.balance(current_energy, initial_energy) / reference
          << " (largest " << largest_balance / reference << ")\n"
          << "  largest plastic strain:   " << largest_plastic_strain << "\n";
    if (implicit)
      {
        pcout << "  energy change by the grid step / " << scale << " = "
              << grid_energy_change / reference << "\n";
        const double steps = std::max(1U, step_number());
        pcout << "  Newton iterations per step (mean, max): "
              << implicit_totals.newton_iterations / steps << ", "
              << implicit_totals.max_newton_iterations << "\n"
              << "  linear iterations per Newton iteration: "
              << (implicit_totals.newton_iterations > 0 ?
                    static_cast<double>(implicit_totals.linear_iterations) /
                      implicit_totals.newton_iterations :
                    0.)
              << "\n"
              << "  residual evaluations per step:          "
              << implicit_totals.residual_evaluations / steps << "\n"
              << "  contact status changes:                 "
              << implicit_totals.status_changes << "\n"
              << "  rejected steps:                         "
              << implicit_totals.rejected << "\n";
        if (implicit_totals.rejected > 0)
          pcout << "  smallest time step tried:               "
                << implicit_totals.smallest_step << "\n";
      }
    // Momentum relative to the initial momentum scale sum_p m_p |v_p|; walls,
    // rigid grains, gravity and removed particles change it legitimately.
    const double momentum_change =
      (current_energy.momentum - initial_energy.momentum).norm();
    if (initial_momentum_scale > 0.)
      {
        const double relative = momentum_change / initial_momentum_scale;
        pcout << "  |momentum(end) - momentum(0)| / sum m|v|(0) = "
              << (relative < 1e-12 ? 0. : relative)
              << (relative < 1e-10 ? "  (conserved to 1e-10)" : "  (changed)");
      }
    else
      pcout << "  |momentum(end) - momentum(0)| = " << momentum_change;
    pcout << std::endl;

    // Peak resident memory (machine-dependent, so not in test mode).
    if (!parameters.output.test_mode)
      {
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double peak = memory.VmHWM / 1024.; // MiB
        pcout << "  peak memory: " << Utilities::MPI::sum(peak, communicator)
              << " MiB summed over "
              << Utilities::MPI::n_mpi_processes(communicator)
              << " ranks, largest rank "
              << Utilities::MPI::max(peak, communicator) << " MiB" << std::endl;
      }
  }



  template <int dim>
  void
  run(const std::string &filename, const MPI_Comm communicator)
  {
    ParameterHandler prm;
    Parameters<dim>  parameters;
    parameters.parse(filename, prm);
    add_random_packing(parameters);
    Simulator<dim> simulator(parameters, prm, filename, communicator);
    simulator.run();
  }



  template <int dim>
  template <class Archive>
  void
  Simulator<dim>::serialize_state(Archive &archive)
  {
    archive &start_time &next_step_size &step_offset &next_output &step_limit;
    archive &easy_steps &n_contact_steps &minimum_time_step;
    archive &n_outputs &n_removed &n_held_at_walls &initial_energy
                                                                &current_energy;
    archive &minimum_energy &maximum_energy &grid_energy_change &ledger;
    archive &largest_balance &largest_kinetic_elastic &initial_momentum_scale;
    archive &implicit_totals.newton_iterations &implicit_totals
      .linear_iterations &implicit_totals.residual_evaluations &implicit_totals
      .status_changes &implicit_totals.max_newton_iterations &implicit_totals
      .rejected &implicit_totals.smallest_step;
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
  Simulator<dim>::write_checkpoint()
  {
    // Everything goes to a temporary directory, which is renamed when
    // complete: a run killed meanwhile leaves the older checkpoints intact.
    const std::string  directory = parameters.output.directory;
    std::ostringstream name;
    name << directory << "/checkpoint-" << std::setw(6) << std::setfill('0')
         << step_offset;
    const std::string final_name     = name.str();
    const std::string temporary_name = final_name + ".tmp";
    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    if (root)
      {
        std::filesystem::remove_all(temporary_name);
        std::filesystem::create_directories(temporary_name);
      }
    MPI_Barrier(communicator);

    particle_handler.prepare_for_serialization();
    grid.get_triangulation().save(temporary_name + "/grid");
    if (root)
      {
        std::ofstream out(temporary_name + "/state", std::ios::binary);
        boost::archive::binary_oarchive archive(out);
        std::uintmax_t energy_length = energy_history->length();
        std::uintmax_t grains_length =
          grain_history != nullptr ? grain_history->length() : 0;
        archive << energy_length << grains_length;
        serialize_state(archive);
        archive << *energy_history << *output_writer;
      }
    MPI_Barrier(communicator);
    if (root)
      {
        std::filesystem::remove_all(final_name);
        std::filesystem::rename(temporary_name, final_name);
        checkpoints.erase(std::remove(checkpoints.begin(),
                                      checkpoints.end(),
                                      final_name),
                          checkpoints.end());
        checkpoints.push_back(final_name);
        while (checkpoints.size() > parameters.checkpoint.n_kept)
          {
            std::filesystem::remove_all(checkpoints.front());
            checkpoints.erase(checkpoints.begin());
          }
      }
  }



  template <int dim>
  void
  Simulator<dim>::run()
  {
    // On an error, end without the timing table (TimerOutput would warn
    // that it cannot synchronise while an exception is in flight).
    try
      {
        advance_to_end_time();
      }
    catch (...)
      {
        timer.disable_output();
        throw;
      }
  }



  template class Simulator<2>;
  template class Simulator<3>;
  template void
  run<2>(const std::string &, const MPI_Comm);
  template void
  run<3>(const std::string &, const MPI_Comm);
} // namespace grainmpm
