// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/run_summary.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace grainmpm
{
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
    residual_evaluations += statistics.residual_evaluations;
    if (!statistics.converged)
      ++rejected;
  }



  template <int dim>
  void
  RunSummary<dim>::add_step(const StepStatistics &statistics)
  {
    if (implicit)
      {
        newton_iterations += statistics.newton_iterations;
        linear_iterations += statistics.linear_iterations;
        status_changes += statistics.status_changes;
        max_newton_iterations =
          std::max(max_newton_iterations, statistics.newton_iterations);
      }
    grid_energy_change += statistics.grid_energy_change;
    ledger.add(statistics);
    n_removed += statistics.n_removed;
    n_held_at_walls += statistics.n_held_at_walls;
    if (statistics.n_contact_nodes > 0)
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
    const bool        starts_at_rest = !(initial_energy.total() > 0.);
    const double      reference      = starts_at_rest ?
                                         std::max(largest_kinetic_elastic, 1e-300) :
                                         initial_energy.total();
    const std::string scale          = starts_at_rest ? "E_max" : "E_total(0)";
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
    out << ", balance residual = "
        << ledger.balance(current_energy, initial_energy) / reference
        << " (largest " << largest_balance / reference << ")\n"
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



  template class RunSummary<2>;
  template class RunSummary<3>;
} // namespace grainmpm
