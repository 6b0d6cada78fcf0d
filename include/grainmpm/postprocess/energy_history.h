// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_energy_history_h
#define grainmpm_postprocess_energy_history_h

#include <grainmpm/base/config.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/postprocess/history_file.h>
#include <grainmpm/time_integration/time_integrator.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/serialization/version.hpp>

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * The global energies and momentum of the deformable grains (rigid grains
   * are external bodies and are left out). In 2D all are per unit thickness.
   */
  template <int dim>
  struct EnergySummary
  {
    /** sum_p 1/2 m_p |v_p|^2. */
    double kinetic = 0.;
    /** sum_p V_p 1/2 sigma_p : C^{-1} : sigma_p. */
    double elastic = 0.;
    /**
     * Gravity potential relative to the start, -g . (sum_p m_p x_p -
     * sum_p m_p x_p(0)).
     */
    double gravity = 0.;
    /** sum_p m_p v_p. */
    Tensor<1, dim> momentum;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &kinetic &elastic &gravity &momentum;
    }

    /** Kinetic, elastic and gravity energy. */
    double
    total() const
    {
      return kinetic + elastic + gravity;
    }
  };

  /**
   * The energy ledger of a run: what left the deformable grains' kinetic,
   * elastic and gravity energy, and where it went, summed from the start
   * (StepStatistics of the accepted steps). The balance residual is what
   * none of these accounts for: the time integrator's own gain or loss
   * (explicit: the oscillating rest of the leapfrog's exchange, all of it
   * with USF and MUSL; implicit: the contact pass on v^n, the theta
   * step), and particles removed through open faces.
   */
  struct EnergyLedger
  {
    /** Plastic work, >= 0. */
    double plastic_work = 0.;
    /** Work taken out by friction at contacts and walls, >= 0. */
    double friction_work = 0.;
    /** Work put in by rigid grains (and walls, which are at rest). */
    double boundary_work = 0.;
    /**
     * Energy the explicit leapfrog's exchange between kinetic and strain
     * energy added (<= 0, LedgerIncrements::leapfrog_energy_change); 0
     * implicit.
     */
    double leapfrog = 0.;
    /**
     * Energy the grid-to-particle transfers added (FLIP: <= 0, the
     * lumped-mass loss).
     */
    double transfer = 0.;
    /**
     * The elastic energy sum V W(sigma) less the elastic work of the
     * stresses (LedgerIncrements::hypoelastic_correction): what the
     * elastic energy column shows beyond the energy the grains store.
     */
    double hypoelastic_correction = 0.;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version)
    {
      archive &plastic_work &friction_work &boundary_work &leapfrog &transfer;
      if (version >= 1)
        archive &hypoelastic_correction;
    }

    /** Add the step's entries. */
    void
    add(const StepStatistics &statistics)
    {
      plastic_work += statistics.ledger.plastic_work;
      friction_work += statistics.ledger.friction_work;
      boundary_work += statistics.ledger.boundary_work;
      leapfrog += statistics.ledger.leapfrog_energy_change;
      transfer += statistics.ledger.transfer_energy_change;
      hypoelastic_correction += statistics.ledger.hypoelastic_correction;
    }

    /**
     * E(now) - E(0) + plastic + friction - boundary - transfer
     * - leapfrog - hypoelastic correction: zero for an exact balance.
     */
    template <int dim>
    double
    balance(const EnergySummary<dim> &now,
            const EnergySummary<dim> &initial) const
    {
      return now.total() - initial.total() + plastic_work + friction_work -
             boundary_work - transfer - leapfrog - hypoelastic_correction;
    }
  };

  /**
   * Computes the energy summary every step and writes it as one flushed row
   * of `energy.csv`, whose header names every column with its unit (in the
   * consistent unit system of the input: M mass, L length, T time).
   */
  template <int dim>
  class EnergyHistory
  {
  public:
    EnergyHistory(
      const std::string                                          &filename,
      const std::vector<GrainInfo<dim>>                          &grains,
      const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials,
      const Tensor<1, dim>                                       &gravity,
      const MPI_Comm                                              communicator,
      const std::uintmax_t resume_length = 0);

    /** The length of the file so far (for a checkpoint). */
    std::uintmax_t
    length();

    /** Checkpoint the zero of the gravity potential. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &initial_moment &have_initial_moment;
    }

    /**
     * The summary of the particles of @p particle_handler; the first call
     * fixes the zero of the gravity potential.
     */
    EnergySummary<dim>
    compute(const Particles::ParticleHandler<dim> &particle_handler);

    /**
     * The same from the particle sums a step gathered and reduced
     * (ParticleSums::has_particle_sums); not collective.
     */
    EnergySummary<dim>
    summarize(const StepStatistics &statistics);

    /**
     * Stop every rank with a message naming the file if a write has failed.
     * Collective.
     */
    void
    check_written() const;

    /** Append one row. */
    void
    write_row(const unsigned int        step,
              const double              time,
              const double              dt,
              const EnergySummary<dim> &summary,
              const StepStatistics     &statistics,
              const EnergyLedger       &ledger,
              const EnergySummary<dim> &initial);

  private:
    const Tensor<1, dim> gravity;
    /** sum_p m_p x_p at the first compute(). */
    Tensor<1, dim>                     initial_moment;
    bool                               have_initial_moment = false;
    const std::vector<GrainInfo<dim>> &grains;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;
    const MPI_Comm                                              communicator;
    HistoryFile                                                 file;
  };
} // namespace grainmpm

/**
 * Version 1 of the ledger adds the hypoelastic correction; a checkpoint
 * of version 0 resumes with it zero.
 */
BOOST_CLASS_VERSION(grainmpm::EnergyLedger, 1)

#endif
