// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/postprocess/run_summary.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <string>

namespace grainmpm
{
  void
  append_measured_rows(std::vector<SummaryRow>   &rows,
                       const double               wall_time,
                       const dealii::TimerOutput &timer,
                       const double               memory_sum,
                       const double               memory_largest)
  {
    rows.push_back({"wall_time", wall_time, "s"});
    for (const auto &[section, seconds] :
         timer.get_summary_data(dealii::TimerOutput::total_wall_time))
      {
        std::string name = "wall_time_" + section;
        std::replace(name.begin(), name.end(), ' ', '_');
        rows.push_back({name, seconds, "s"});
      }
    rows.push_back({"peak_memory", memory_sum, "MiB"});
    rows.push_back({"peak_memory_largest_rank", memory_largest, "MiB"});
  }



  void
  write_summary_file(const std::string             &filename,
                     const std::vector<SummaryRow> &rows,
                     const MPI_Comm                 communicator)
  {
    std::string error;
    if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        // Complete or absent: written under a temporary name, then renamed.
        const std::string temporary = filename + ".tmp";
        std::ofstream     out(temporary);
        out << "quantity,value,unit\n" << std::setprecision(17);
        for (const SummaryRow &row : rows)
          out << row.quantity << ',' << row.value << ',' << row.unit << '\n';
        out.close();
        std::error_code code;
        if (out)
          std::filesystem::rename(temporary, filename, code);
        if (!out || code)
          {
            std::filesystem::remove(temporary, code);
            error = InputError("Output/Output directory",
                               "could not write '" + filename +
                                 "' (disk full, or no permission?).")
                      .what();
          }
      }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  RunSummary<dim>::RunSummary(const bool implicit)
    : implicit(implicit)
  {}



  template <int dim>
  void
  RunSummary<dim>::start(const EnergySummary<dim> &initial,
                         const double              momentum_scale)
  {
    initial_energy = current_energy = initial;
    minimum_energy = maximum_energy = initial.total();
    largest_kinetic_elastic         = initial.kinetic + initial.elastic;
    initial_momentum_scale          = momentum_scale;
  }



  template <int dim>
  void
  RunSummary<dim>::add_attempt(const StepStatistics &statistics)
  {
    residual_evaluations += statistics.solver.residual_evaluations;
    if (!statistics.solver.converged)
      ++rejected;
  }



  template <int dim>
  void
  RunSummary<dim>::add_step(const StepStatistics &statistics)
  {
    if (implicit)
      {
        newton_iterations += statistics.solver.newton_iterations;
        linear_iterations += statistics.solver.linear_iterations;
        status_changes += statistics.solver.status_changes;
        if (statistics.solver.explicit_substeps > 0)
          ++fallback_steps;
        explicit_substeps += statistics.solver.explicit_substeps;
        max_newton_iterations =
          std::max(max_newton_iterations, statistics.solver.newton_iterations);
      }
    grid_energy_change += statistics.ledger.grid_energy_change;
    ledger.add(statistics);
    n_removed += statistics.events.n_removed;
    n_held_at_walls += statistics.events.n_held_at_walls;
    if (statistics.events.n_contact_nodes > 0)
      ++n_contact_steps;
  }



  template <int dim>
  void
  RunSummary<dim>::add_energies(const EnergySummary<dim> &current)
  {
    current_energy = current;
    minimum_energy = std::min(minimum_energy, current.total());
    maximum_energy = std::max(maximum_energy, current.total());
    largest_kinetic_elastic =
      std::max(largest_kinetic_elastic, current.kinetic + current.elastic);
    largest_balance =
      std::max(largest_balance,
               std::abs(ledger.balance(current, initial_energy)));
  }



  template <int dim>
  bool
  RunSummary<dim>::starts_at_rest() const
  {
    return !(initial_energy.total() > 0.);
  }



  template <int dim>
  double
  RunSummary<dim>::energy_reference() const
  {
    return starts_at_rest() ? std::max(largest_kinetic_elastic, 1e-300) :
                              initial_energy.total();
  }



  template <int dim>
  void
  RunSummary<dim>::print(std::ostream               &out,
                         const unsigned int          n_steps,
                         const double                time,
                         const types::particle_index n_lost,
                         const types::particle_index n_points,
                         const double                largest_plastic_strain,
                         const double                smallest_step_tried) const
  {
    // Final summary: O(1) numbers, fit for the regression tests. Energies
    // are relative to the initial total energy, or to the largest one if
    // the run starts at rest.
    const double      reference = energy_reference();
    const std::string scale     = starts_at_rest() ? "E_max" : "E_total(0)";
    out << "\nfinished: " << n_steps << " steps to t = " << time << "\n"
        << "  steps with contact:       " << n_contact_steps << "\n"
        << "  particles removed:        " << n_removed + n_lost << "\n"
        << "  material points left:     " << n_points << "\n";
    if (n_held_at_walls > 0)
      out << "  points held at walls:     " << n_held_at_walls
          << " times (carried less than half a cell through a closed "
             "face)\n";
    out << "  E_total(end) / " << scale << " = "
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
        << ", boundary work = " << ledger.boundary_work / reference;
    out << ", transfers = " << ledger.transfer / reference;
    if (!implicit)
      out << ", leapfrog = " << ledger.leapfrog / reference;
    out << ", hypoelastic correction = "
        << ledger.hypoelastic_correction / reference
        << ", balance residual = " << relative_balance() << " (largest "
        << largest_balance / reference << ")\n"
        << "  largest plastic strain:   " << largest_plastic_strain << "\n";
    if (implicit)
      {
        out << "  energy change by the grid step / " << scale << " = "
            << grid_energy_change / reference << "\n";
        const double steps = std::max(1U, n_steps);
        out << "  Newton iterations per step (mean, max): "
            << newton_iterations / steps << ", " << max_newton_iterations
            << "\n"
            << "  linear iterations per Newton iteration: "
            << (newton_iterations > 0 ?
                  static_cast<double>(linear_iterations) / newton_iterations :
                  0.)
            << "\n"
            << "  residual evaluations per step:          "
            << residual_evaluations / steps << "\n"
            << "  contact status changes:                 " << status_changes
            << "\n"
            << "  rejected steps:                         " << rejected << "\n";
        if (rejected > 0)
          out << "  smallest time step tried:               "
              << smallest_step_tried << "\n";
        if (fallback_steps > 0)
          out << "  steps advanced by explicit sub-steps:   " << fallback_steps
              << " (" << explicit_substeps << " sub-steps)\n";
      }
    // Momentum relative to the initial momentum scale sum_p m_p |v_p|; walls,
    // rigid grains, gravity and removed particles change it legitimately.
    const double momentum_change =
      (current_energy.momentum - initial_energy.momentum).norm();
    if (initial_momentum_scale > 0.)
      {
        const double relative = momentum_change / initial_momentum_scale;
        out << "  |momentum(end) - momentum(0)| / sum m|v|(0) = "
            << (relative < 1e-12 ? 0. : relative)
            << (relative < 1e-10 ? "  (conserved to 1e-10)" : "  (changed)");
      }
    else
      out << "  |momentum(end) - momentum(0)| = " << momentum_change;
    out << std::endl;
  }



  template <int dim>
  std::vector<SummaryRow>
  RunSummary<dim>::rows(const unsigned int          n_steps,
                        const double                time,
                        const types::particle_index n_lost,
                        const types::particle_index n_points,
                        const double                largest_plastic_strain,
                        const double                smallest_step_tried) const
  {
    // The same expressions as in print(), so that the values agree with
    // the screen to its six digits.
    const double      reference = energy_reference();
    const std::string energy    = (dim == 2 ? "M L^2/T^2 per L" : "M L^2/T^2");
    const std::string impulse   = (dim == 2 ? "M L/T per L" : "M L/T");
    const std::string relative  = "E_ref";
    const double      steps     = std::max(1U, n_steps);
    const double      momentum_change =
      (current_energy.momentum - initial_energy.momentum).norm();
    std::vector<SummaryRow> rows = {
      {"implicit_scheme", implicit ? 1. : 0., "1"},
      {"steps", static_cast<double>(n_steps), "1"},
      {"end_time", time, "T"},
      {"contact_steps", static_cast<double>(n_contact_steps), "1"},
      {"removed_particles", static_cast<double>(n_removed + n_lost), "1"},
      {"material_points", static_cast<double>(n_points), "1"},
      {"points_held_at_walls", static_cast<double>(n_held_at_walls), "1"},
      {"starts_at_rest", starts_at_rest() ? 1. : 0., "1"},
      {"energy_reference", reference, energy},
      {"total_energy_end", current_energy.total() / reference, relative},
      {"total_energy_min", minimum_energy / reference, relative},
      {"total_energy_max", maximum_energy / reference, relative},
      {"kinetic_energy_end", current_energy.kinetic / reference, relative},
      {"elastic_energy_end", current_energy.elastic / reference, relative},
      {"plastic_work", ledger.plastic_work / reference, relative},
      {"friction_work", ledger.friction_work / reference, relative},
      {"boundary_work", ledger.boundary_work / reference, relative},
      {"transfer_work", ledger.transfer / reference, relative},
      {"leapfrog_work", ledger.leapfrog / reference, relative},
      {"hypoelastic_correction",
       ledger.hypoelastic_correction / reference,
       relative},
      {"balance_residual", relative_balance(), relative},
      {"largest_balance_residual", largest_balance / reference, relative},
      {"grid_energy_change", grid_energy_change / reference, relative},
      {"largest_plastic_strain", largest_plastic_strain, "1"},
      {"newton_iterations", static_cast<double>(newton_iterations), "1"},
      {"newton_iterations_per_step", newton_iterations / steps, "1"},
      {"newton_iterations_max",
       static_cast<double>(max_newton_iterations),
       "1"},
      {"linear_iterations", static_cast<double>(linear_iterations), "1"},
      {"linear_iterations_per_newton_iteration",
       newton_iterations > 0 ?
         static_cast<double>(linear_iterations) / newton_iterations :
         0.,
       "1"},
      {"residual_evaluations", static_cast<double>(residual_evaluations), "1"},
      {"residual_evaluations_per_step", residual_evaluations / steps, "1"},
      {"contact_status_changes", static_cast<double>(status_changes), "1"},
      {"rejected_steps", static_cast<double>(rejected), "1"},
      {"smallest_time_step_tried", smallest_step_tried, "T"},
      {"explicit_fallback_steps", static_cast<double>(fallback_steps), "1"},
      {"explicit_substeps", static_cast<double>(explicit_substeps), "1"},
      {"momentum_change", momentum_change, impulse},
      {"momentum_scale", initial_momentum_scale, impulse}};
    if (initial_momentum_scale > 0.)
      rows.push_back({"momentum_change_relative",
                      momentum_change / initial_momentum_scale,
                      "1"});
    return rows;
  }



  template class RunSummary<2>;
  template class RunSummary<3>;
} // namespace grainmpm
