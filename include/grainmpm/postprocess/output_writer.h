// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_output_writer_h
#define grainmpm_postprocess_output_writer_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/postprocess/contact_history.h>
#include <grainmpm/postprocess/grain_history.h>
#include <grainmpm/time_integration/time_integrator.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/particles/particle_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace grainmpm
{
  /**
   * Writes the ParaView files of a run (README, Running):
   * `particles.pvd` with `particles/particles_NNNNN.vtu` (position and the
   * fields of particle_fields()) and `grid.pvd` with
   * `grid/grid_NNNNN.vtu` (nodal mass, centre-of-mass velocity, number of
   * grains, contact flag). The .pvd records are members, rewritten after every
   * output, so a run that stops keeps a valid time series of what was written.
   */
  template <int dim>
  class OutputWriter
  {
  public:
    /**
     * @p fringe_factors holds, per grain, thickness / material fringe value
     * of its material (0 if it is not photoelastic): the fringe order of a
     * particle is that factor times its principal stress difference.
     */
    OutputWriter(const OutputParameters    &parameters,
                 const BackgroundGrid<dim> &grid,
                 const std::vector<double> &fringe_factors);

    /** Write the particles at @p time as output number @p index. */
    void
    write_particles(const Particles::ParticleHandler<dim> &particle_handler,
                    const double                           time,
                    const unsigned int                     index);

    /** Write the grid fields of the last step of @p stepper. */
    void
    write_grid(const TimeIntegrator<dim> &stepper,
               const double               time,
               const unsigned int         index);

    /**
     * Write the force chains of @p forces at @p time as output number
     * @p index (rank 0 has the forces): a line per pair of grains from
     * centre to centre (@p motions), or from the deformable grain's centre
     * to the contact point if the partner is rigid, with the pair's forces
     * as cell data. Collective.
     */
    void
    write_contacts(const std::vector<GrainContactForce<dim>> &forces,
                   const std::vector<GrainMotion<dim>>       &motions,
                   const std::vector<bool>                   &rigid,
                   const double                               time,
                   const unsigned int                         index);

    /**
     * Prefix the file names of the .pvd records with @p prefix (a path
     * relative to the output directory), for a run resumed in another
     * output directory than its checkpoint's: the records up to the
     * checkpoint then name the files of the run that wrote them.
     */
    void
    prefix_records(const std::string &prefix)
    {
      for (auto *records : {&particle_records, &grid_records, &contact_records})
        for (auto &record : *records)
          record.second = prefix + "/" + record.second;
    }

    /** Checkpoint the .pvd records. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &particle_records &grid_records &contact_records;
    }

  private:
    const OutputParameters                     &parameters;
    const BackgroundGrid<dim>                  &grid;
    const std::vector<double>                   fringe_factors;
    FESystem<dim>                               vector_fe;
    DoFHandler<dim>                             vector_dof_handler;
    std::vector<std::pair<double, std::string>> particle_records;
    std::vector<std::pair<double, std::string>> grid_records;
    std::vector<std::pair<double, std::string>> contact_records;
  };
} // namespace grainmpm

#endif
