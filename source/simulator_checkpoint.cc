// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The checkpoints of the time loop: when to write one (with the load
// balance before it), writing it, the state it keeps, and a stop on a
// signal.

#include <grainmpm/base/stop_signals.h>
#include <grainmpm/contact/held_contact_status.h>
#include <grainmpm/simulator.h>
#include <grainmpm/time_integration/step_error_estimator.h>

#include <deal.II/base/utilities.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <csignal>
#include <sstream>
#include <string>

namespace grainmpm
{
  template <int dim>
  void
  Simulator<dim>::repartition_and_checkpoint(const unsigned int  step,
                                             const DiscreteTime &time)
  {
    // Repartition after the output (the grid output reads the slot layout
    // of the step), at the interval and before a checkpoint: a resumed run
    // repartitions first, by the same weights.
    const bool checkpoint_now = schedule.checkpoint_due(step, time.is_at_end());
    const unsigned int balance_interval =
      parameters.load_balancing.steps_between;
    if (!time.is_at_end() && (checkpoint_now || (balance_interval > 0 &&
                                                 step % balance_interval == 0)))
      balance_load();
    if (checkpoint_now)
      write_checkpoint(step, time);
  }



  template <int dim>
  void
  Simulator<dim>::write_checkpoint(const unsigned int  step,
                                   const DiscreteTime &time)
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    // Rank 0 writes the state: the contact sums of the interval go there.
    postprocessor->prepare_checkpoint();
    // The state is that of a run starting here.
    const unsigned int offset = step_offset;
    start_time                = time.get_current_time();
    next_step_size            = time.get_next_step_size();
    step_offset               = step;
    checkpoints->write(
      step,
      CheckpointManager<dim>::fingerprint(parameters, grains),
      grid,
      particle_handler,
      [this](boost::archive::binary_oarchive &archive) {
        const typename Postprocessor<dim>::HistoryLengths lengths =
          postprocessor->get_lengths();
        archive << lengths.energy << lengths.grains << lengths.walls
                << lengths.contacts << *this;
        postprocessor->serialize(archive, 0);
      });
    step_offset = offset;
    schedule.checkpoint_written();
    last_checkpoint_step = step;
  }



  template <int dim>
  void
  Simulator<dim>::stop(const int           signal,
                       const unsigned int  step,
                       const DiscreteTime &time)
  {
    const std::string name = signal == SIGINT  ? "SIGINT" :
                             signal == SIGTERM ? "SIGTERM" :
                                                 std::to_string(signal);
    pcout << "  " << name << " received: stopping after step " << step
          << std::endl;
    if (last_output_step != step)
      write_output(step,
                   time.get_current_time(),
                   time.get_previous_step_size(),
                   schedule.extra_output_written());
    const bool checkpointing = parameters.checkpoint.steps_between > 0 ||
                               parameters.checkpoint.minutes_between > 0.;
    if (checkpointing && last_checkpoint_step != step)
      {
        balance_load();
        write_checkpoint(step, time);
      }
    print_summary(step, time.get_current_time());

    std::ostringstream message;
    message << "stopped by " << name << " after step " << step
            << " at t = " << time.get_current_time()
            << ". The output up to this time is "
            << "complete in " << parameters.output.directory << ". ";
    if (checkpointing)
      message << "To go on, set Checkpoint/Resume from = "
              << parameters.output.directory << "/checkpoint-"
              << Utilities::int_to_string(step, 6) << " and run again.";
    else
      message << "Checkpointing is off (Checkpoint/Steps between "
                 "checkpoints = 0), so the run cannot be resumed from here.";
    throw RunStopped(signal, message.str());
  }



  template <int dim>
  template <class Archive>
  void
  Simulator<dim>::serialize(Archive &archive, const unsigned int version)
  {
    archive &start_time &next_step_size      &step_offset;
    archive &*time_step_controller &schedule &summary;
    // The contact status the implicit scheme starts its next step from
    // (empty for the explicit scheme; read and dropped by it).
    if (version >= 1)
      {
        HeldContactStatus<dim>  none;
        HeldContactStatus<dim> *held = stepper->get_held_contact_status();
        archive &(held != nullptr ? *held : none);
      }
    // The length of the step whose accelerations the points hold, for
    // the error estimate of the implicit scheme's next step.
    if (version >= 2)
      {
        StepErrorEstimator<dim>  none(grains);
        StepErrorEstimator<dim> *estimator =
          stepper->get_step_error_estimator();
        archive &(estimator != nullptr ? *estimator : none);
      }
    // Whether the last implicit step was quasi-static, which chooses the
    // centring of the next one (Quasi-static theta).
    if (version >= 3)
      {
        bool  none         = false;
        bool *quasi_static = stepper->get_quasi_static_flag();
        archive &(quasi_static != nullptr ? *quasi_static : none);
      }
    // Where the contact locates the rigid grains, carried from step to
    // step (an older checkpoint: located afresh from the points).
    if (version >= 4)
      archive & * stepper->get_rigid_grain_motion();
  }



  template void
  Simulator<2>::repartition_and_checkpoint(const unsigned int,
                                           const DiscreteTime &);
  template void
  Simulator<3>::repartition_and_checkpoint(const unsigned int,
                                           const DiscreteTime &);
  template void
  Simulator<2>::stop(const int, const unsigned int, const DiscreteTime &);
  template void
  Simulator<3>::stop(const int, const unsigned int, const DiscreteTime &);
  template void
  Simulator<2>::serialize(boost::archive::binary_iarchive &,
                          const unsigned int);
  template void
  Simulator<3>::serialize(boost::archive::binary_iarchive &,
                          const unsigned int);
} // namespace grainmpm
