// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_postprocessor_h
#define grainmpm_postprocess_postprocessor_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/base/step_statistics.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/postprocess/contact_history.h>
#include <grainmpm/postprocess/energy_history.h>
#include <grainmpm/postprocess/grain_history.h>
#include <grainmpm/postprocess/output_writer.h>
#include <grainmpm/postprocess/reaction_history.h>
#include <grainmpm/time_integration/time_integrator.h>

#include <deal.II/particles/particle_handler.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace grainmpm
{
  /**
   * The output of a run, apart from the screen: the particle, grid and
   * force-chain files (OutputWriter), and the histories energy.csv,
   * grains.csv, walls.csv and contacts.csv. The Simulator calls it after
   * every step and at every output time; it owns the writers and keeps
   * them consistent with a checkpoint (serialize()).
   */
  template <int dim>
  class Postprocessor
  {
  public:
    /**
     * How many bytes the history files had when a checkpoint was written:
     * a resumed run cuts them back to these lengths.
     */
    struct HistoryLengths
    {
      std::uintmax_t energy   = 0;
      std::uintmax_t grains   = 0;
      std::uintmax_t walls    = 0;
      std::uintmax_t contacts = 0;
    };

    /**
     * Open the history files in `Output/Output directory` (cut back to
     * @p lengths, or new if they are zero) for the grains @p grains and
     * their materials @p materials, whose material points are in
     * @p particle_handler (for the centres of the rigid grains).
     */
    Postprocessor(
      const Parameters<dim>                                      &parameters,
      const BackgroundGrid<dim>                                  &grid,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
      const Particles::ParticleHandler<dim> &particle_handler,
      const HistoryLengths                  &lengths,
      const MPI_Comm                         communicator);

    /**
     * A run resumed in another output directory than its checkpoint's
     * (CheckpointManager::resume_source()): start the history files in
     * @p directory as copies of those in @p source, which had @p lengths
     * at the checkpoint (copy_history_file()). Rank 0 copies; an error
     * stops every rank. Collective.
     */
    static void
    copy_histories(const std::string    &source,
                   const std::string    &directory,
                   const HistoryLengths &lengths,
                   const MPI_Comm        communicator);

    /** The lengths of the history files now (for a checkpoint). */
    HistoryLengths
    get_lengths() const;

    /**
     * The energies of the material points in @p particle_handler, or of
     * the sums the step gathered in @p statistics if it did.
     */
    EnergySummary<dim>
    compute_energies(const Particles::ParticleHandler<dim> &particle_handler,
                     const StepStatistics                  &statistics);

    /**
     * The largest speed of the rigid-body motion of a grain (GrainMotion):
     * the speed of its centre of mass plus its angular speed times the
     * largest distance of its points from the centre. Collective.
     */
    double
    largest_grain_speed(
      const Particles::ParticleHandler<dim> &particle_handler) const;

    /** The first row of energy.csv, with the @p initial energies. */
    void
    write_initial_row(const EnergySummary<dim> &initial,
                      const EnergyLedger       &ledger);

    /**
     * The rows of step @p step (ending at @p time, of length @p dt) of
     * walls.csv and energy.csv (energies @p energies, the step's
     * @p statistics, the ledger of @p summary), and the contact impulses
     * of the step into the sums of contacts.csv.
     */
    void
    write_step(const unsigned int                     step,
               const double                           time,
               const double                           dt,
               const StepStatistics                  &statistics,
               const ConstraintImpulses<dim>         &impulses,
               const EnergySummary<dim>              &energies,
               const EnergyLedger                    &ledger,
               const EnergySummary<dim>              &initial_energies,
               const Particles::ParticleHandler<dim> &particle_handler);

    /**
     * The output at @p time after step @p step, number @p index of the
     * series: material points, grid fields of @p stepper (after the first
     * step), grains.csv, contacts.csv and the force chains, as `Output`
     * asks. Stops every rank if a history file could not be written.
     */
    void
    write_output(const unsigned int                     step,
                 const double                           time,
                 const unsigned int                     index,
                 const Particles::ParticleHandler<dim> &particle_handler,
                 const TimeIntegrator<dim>             &stepper);

    /**
     * Before a checkpoint: gather on rank 0 what the contact history has
     * summed since the last output, so that the state written holds it.
     */
    void
    prepare_checkpoint();

    /** OutputWriter::prefix_records(). */
    void
    prefix_output_records(const std::string &prefix)
    {
      output_writer->prefix_records(prefix);
    }

    /**
     * Read or write the state of the writers and histories. Called directly
     * (not through `archive & postprocessor`), so that the archive holds
     * the members only.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version);

  private:
    const Parameters<dim> &parameters;
    /** Per grain: whether it is rigid. */
    std::vector<bool>                     grain_is_rigid;
    const unsigned int                    n_grains;
    std::unique_ptr<OutputWriter<dim>>    output_writer;
    std::unique_ptr<EnergyHistory<dim>>   energy_history;
    std::unique_ptr<GrainHistory<dim>>    grain_history;
    std::unique_ptr<ReactionHistory<dim>> reaction_history;
    /** Only with `Output/Write contacts`. */
    std::unique_ptr<ContactHistory<dim>> contact_history;
  };



  template <int dim>
  template <class Archive>
  void
  Postprocessor<dim>::serialize(Archive &archive, const unsigned int)
  {
    archive &*energy_history &*output_writer &*grain_history &*reaction_history;
    if (contact_history)
      archive &*contact_history;
  }
} // namespace grainmpm

#endif
