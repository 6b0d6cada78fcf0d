// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_energy_history_h
#define grainmpm_postprocess_energy_history_h

#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/time_integration/time_integrator.h>

#include <deal.II/particles/particle_handler.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace grainmpm
{
  using namespace dealii;

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
    /** sum_p m_p v_p. */
    Tensor<1, dim> momentum;

    double
    total() const
    {
      return kinetic + elastic;
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
      const MPI_Comm                                              communicator);

    /** The summary of the particles of @p particle_handler. */
    EnergySummary<dim>
    compute(const Particles::ParticleHandler<dim> &particle_handler) const;

    /** Append one row. */
    void
    write_row(const unsigned int        step,
              const double              time,
              const double              dt,
              const EnergySummary<dim> &summary,
              const StepStatistics     &statistics);

  private:
    const std::vector<GrainInfo<dim>>                          &grains;
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials;
    const MPI_Comm                                              communicator;
    std::ofstream                                               file;
  };
} // namespace grainmpm

#endif
