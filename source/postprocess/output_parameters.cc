// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/postprocess/output_parameters.h>

#include <deal.II/base/patterns.h>

namespace grainmpm
{
  // -------------------------------------------------------------- output

  void
  OutputParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.add_parameter("Output directory",
                      directory,
                      "Directory for all output (created if missing): "
                      "particles.pvd, grid.pvd, contacts.pvd, energy.csv, "
                      "grains.csv, walls.csv, contacts.csv, original.prm "
                      "and parameters.prm. Dimensionless.");
    prm.add_parameter("Output interval",
                      interval,
                      "Simulated time between two graphical outputs and "
                      "grain history rows. Zero writes every step. "
                      "Units: time.",
                      Patterns::Double(0.));
    prm.add_parameter("Write particles",
                      write_particles,
                      "Write particles.pvd and the particle .vtu files.");
    prm.add_parameter("Write grid",
                      write_grid,
                      "Write grid.pvd and the grid .vtu files.");
    prm.add_parameter("Write grain history",
                      write_grain_history,
                      "Write grains.csv (per grain centre of mass, velocity, "
                      "angular velocity, rotation, coordination number) at "
                      "every output.");
    prm.add_parameter("Write contacts",
                      write_contacts,
                      "Write contacts.csv (per pair of grains in contact: "
                      "the mean contact force over the output interval, its "
                      "normal and tangential parts, contact point, normal, "
                      "mobilised friction) and contacts.pvd with the "
                      "contacts/*.vtu force chains (a line between the "
                      "centres of two grains in contact, or from a grain's "
                      "centre to its contact point with a rigid grain) at "
                      "every output.");
    prm.add_parameter("Test mode",
                      test_mode,
                      "Print only what is deterministic (no timings, no "
                      "file names with paths) and a final summary, for the "
                      "regression tests.");
    prm.leave_subsection();
  }



  void
  OutputParameters::check() const
  {
    if (directory.empty())
      throw InputError("Output/Output directory", "must not be empty.");
  }



  // ---------------------------------------------------------- checkpoint

  void
  CheckpointParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    prm.add_parameter("Steps between checkpoints",
                      steps_between,
                      "Write a checkpoint every this many time steps; 0: "
                      "never (by steps). A checkpoint is the directory "
                      "checkpoint-NNNNNN (the step number) in the output "
                      "directory: the triangulation and the material points "
                      "with all properties (deal.II serialization), time, "
                      "time step, step number, the energy ledger and the "
                      "output records. It is written under a temporary "
                      "name and renamed when complete, so a run killed "
                      "while writing leaves the previous checkpoint usable. "
                      "Dimensionless.",
                      Patterns::Integer(0));
    prm.add_parameter("Minutes between checkpoints",
                      minutes_between,
                      "Write a checkpoint when this much wall-clock time has "
                      "passed since the last one (checked after every "
                      "step); 0: never (by time). Units: minutes.",
                      Patterns::Double(0.));
    prm.add_parameter("Checkpoints kept",
                      n_kept,
                      "How many of the newest checkpoints to keep; older "
                      "ones are deleted. Dimensionless.",
                      Patterns::Integer(1));
    prm.add_parameter("Resume from",
                      resume_from,
                      "A checkpoint directory (for example "
                      "results/checkpoint-000100) to continue from; "
                      "energy.csv and grains.csv are cut back to the "
                      "checkpoint and continued. In another Output "
                      "directory than the checkpoint's (to load one "
                      "prepared state in several ways), they start as "
                      "copies of the checkpoint run's up to the checkpoint, "
                      "and the .pvd files name that run's earlier output "
                      "files; the checkpoint's directory is not written "
                      "to. The grid, the materials "
                      "and the grains must be those of the checkpoint's "
                      "run (checked); the contact law, the loading, the "
                      "scheme and its time step, the mass scaling, the end "
                      "time and the output may change. Empty: start at "
                      "t = 0.");
    prm.add_parameter(
      "Replace other checkpoints",
      replace_other_checkpoints,
      "A fresh run (Resume from empty) that writes checkpoints refuses to "
      "start in an output directory that already holds checkpoints, which "
      "belong to another run: they would be replaced or deleted as old. "
      "true: start anyway; those checkpoints are kept, except one that "
      "this run's checkpoint of the same step replaces, and only this "
      "run's own checkpoints are deleted as old.",
      Patterns::Bool());
    prm.add_parameter(
      "Scale velocities with the mass",
      scale_velocities_with_mass,
      "What a run resumed with another Time stepping/Mass scaling than its "
      "checkpoint's does with the velocities of the deformable material "
      "points, whose masses follow the new factor. false: they are kept, "
      "which is right while the velocities are those of the loading (a "
      "packing resumed at the rate it was loaded at). true: they are divided "
      "by the square root of the mass ratio, so that each point keeps its "
      "kinetic energy, which is right for a packing prepared at rest whose "
      "velocities are left-over vibration: a vibration of the same amplitude "
      "is slower by that factor, and kept velocities would give it alpha "
      "times its energy. Either way the ledger's reference moves with the "
      "kinetic energy and momentum that change.",
      Patterns::Bool());
    prm.leave_subsection();
  }
} // namespace grainmpm
