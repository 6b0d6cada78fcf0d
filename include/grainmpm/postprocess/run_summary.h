// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_run_summary_h
#define grainmpm_postprocess_run_summary_h

#include <grainmpm/base/step_statistics.h>
#include <grainmpm/postprocess/energy_history.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * One row of `summary.csv`: the name of a quantity, its value and its
   * unit (`doc/output.md` lists them all).
   */
  struct SummaryRow
  {
    std::string quantity;
    double      value;
    std::string unit;
  };

  /**
   * Append to @p rows the measured figures of a run, which depend on the
   * machine: the wall time @p wall_time of the time loop, the wall time of
   * every section of @p timer that ran, and the peak resident memory
   * summed over the ranks, @p memory_sum, and of the largest rank,
   * @p memory_largest (MiB).
   */
  void
  append_measured_rows(std::vector<SummaryRow>   &rows,
                       const double               wall_time,
                       const dealii::TimerOutput &timer,
                       const double               memory_sum,
                       const double               memory_largest);

  /**
   * Write @p rows as `summary.csv` to @p filename: a header
   * `quantity,value,unit` and one row each, the values to 17 digits.
   * Rank 0 writes the file under a temporary name and renames it when it
   * is complete; a failed write stops every rank with an InputError that
   * names the file. Collective.
   */
  void
  write_summary_file(const std::string             &filename,
                     const std::vector<SummaryRow> &rows,
                     const MPI_Comm                 communicator);

  /**
   * What a run reports when it ends: the energies relative to the initial
   * total energy (or to the largest kinetic plus elastic energy for a run
   * that starts at rest) with their extremes, the energy ledger and its
   * largest balance residual, the counts of contact steps and of removed
   * and held points, the implicit solver totals and the momentum change.
   * Collects them step by step; its state is written to checkpoints by
   * serialize().
   */
  template <int dim>
  class RunSummary
  {
  public:
    /** @p implicit: whether to collect and print the solver totals. */
    explicit RunSummary(const bool implicit);

    /**
     * Start from the @p initial energies and the momentum scale
     * @p momentum_scale = sum_p m_p |v_p| at t = 0.
     */
    void
    start(const EnergySummary<dim> &initial, const double momentum_scale);

    /**
     * The points' masses changed on a resume (another Mass scaling): move
     * the reference energies and momentum (at the start and now) by the
     * change @p kinetic of the kinetic energy and @p momentum of the
     * momentum, so that the balance residual and the momentum change go on
     * from their values at the checkpoint.
     */
    void
    shift_reference(const double kinetic, const Tensor<1, dim> &momentum)
    {
      initial_energy.kinetic += kinetic;
      initial_energy.momentum += momentum;
      current_energy.kinetic += kinetic;
      current_energy.momentum += momentum;
    }

    /** One attempt of a step, accepted or rejected. */
    void
    add_attempt(const StepStatistics &statistics);

    /** An accepted step. */
    void
    add_step(const StepStatistics &statistics);

    /** The energies after an accepted step. */
    void
    add_energies(const EnergySummary<dim> &current);

    /** The energy ledger since the start. */
    const EnergyLedger &
    get_ledger() const
    {
      return ledger;
    }

    const EnergySummary<dim> &
    get_initial_energies() const
    {
      return initial_energy;
    }

    const EnergySummary<dim> &
    get_current_energies() const
    {
      return current_energy;
    }

    /**
     * The balance residual now over the energy reference (the
     * `balance_residual` of summary.csv): positive where the steps
     * created energy.
     */
    double
    relative_balance() const
    {
      return ledger.balance(current_energy, initial_energy) /
             energy_reference();
    }

    /**
     * The balance residual now over the larger of the energy reference and
     * the work the walls and rigid grains have done so far: the energy the
     * steps created, against what the run holds or has been given. (A
     * packing loaded from rest has a tiny energy reference at its first
     * contacts, where the relative balance alone says nothing.)
     */
    double
    created_energy_fraction() const
    {
      return ledger.balance(current_energy, initial_energy) /
             std::max(energy_reference(), std::abs(ledger.boundary_work));
    }

    /**
     * Print the summary of a run that took @p n_steps steps to @p time,
     * lost @p n_lost points in the particle handler and has
     * @p n_points points left, the largest of which equivalent plastic
     * strain is @p largest_plastic_strain; @p smallest_step_tried is the
     * smallest step the failure policy tried.
     */
    void
    print(std::ostream               &out,
          const unsigned int          n_steps,
          const double                time,
          const types::particle_index n_lost,
          const types::particle_index n_points,
          const double                largest_plastic_strain,
          const double                smallest_step_tried) const;

    /**
     * The figures print() prints, with the same arguments, as rows of
     * `summary.csv`: the same values (the energies relative to
     * `energy_reference`), to full precision, and the totals behind the
     * means. Every run has the same rows, those of the implicit solver
     * being 0 for the explicit scheme; `momentum_change_relative` is left
     * out when no point moves at the start.
     */
    std::vector<SummaryRow>
    rows(const unsigned int          n_steps,
         const double                time,
         const types::particle_index n_lost,
         const types::particle_index n_points,
         const double                largest_plastic_strain,
         const double                smallest_step_tried) const;

    /** Read or write the state with @p archive. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &n_contact_steps &n_removed                     &n_held_at_walls;
      archive &initial_energy &current_energy &minimum_energy &maximum_energy;
      archive &grid_energy_change &ledger &largest_balance
        &largest_kinetic_elastic &initial_momentum_scale;
      archive &newton_iterations &linear_iterations &residual_evaluations
        &status_changes &max_newton_iterations &rejected;
      archive &fallback_steps                  &explicit_substeps;
    }

  private:
    /**
     * Whether the run starts at rest (no initial energy): its energies are
     * then reported relative to the largest kinetic plus elastic energy,
     * else relative to the initial total energy.
     */
    bool
    starts_at_rest() const;

    /** The energy the summary's energies are relative to. */
    double
    energy_reference() const;

    const bool implicit;

    unsigned int          n_contact_steps = 0;
    types::particle_index n_removed       = 0;
    types::particle_index n_held_at_walls = 0;
    EnergySummary<dim>    initial_energy;
    EnergySummary<dim>    current_energy;
    double                minimum_energy = 0.;
    double                maximum_energy = 0.;
    /** Sum of the steps' grid energy changes (implicit). */
    double       grid_energy_change = 0.;
    EnergyLedger ledger;
    /** Largest |balance residual| and largest kinetic + elastic energy. */
    double largest_balance         = 0.;
    double largest_kinetic_elastic = 0.;
    /** sum_p m_p |v_p| at t = 0, the scale of momentum errors. */
    double initial_momentum_scale = 0.;

    /** Solver counts of the implicit scheme over the run. */
    unsigned long newton_iterations     = 0;
    unsigned long linear_iterations     = 0;
    unsigned long residual_evaluations  = 0;
    unsigned long status_changes        = 0;
    unsigned int  max_newton_iterations = 0;
    unsigned int  rejected              = 0;
    /** Steps advanced by the explicit fallback, and its sub-steps. */
    unsigned int fallback_steps    = 0;
    unsigned int explicit_substeps = 0;
  };
} // namespace grainmpm

#endif
