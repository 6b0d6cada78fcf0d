// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_checkpoint_manager_h
#define grainmpm_postprocess_checkpoint_manager_h

#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>
#include <grainmpm/particles/grain_generator.h>

#include <deal.II/particles/particle_handler.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace grainmpm
{
  /**
   * Writes and reads checkpoints: a directory checkpoint-NNNNNN (the step)
   * in the output directory with the triangulation and the material points
   * (deal.II serialization, any number of ranks) and a file `state` with
   * the run's own state (a boost binary archive written by rank 0). A
   * checkpoint is written to a temporary directory that is renamed when
   * complete, so a run killed meanwhile leaves the older ones intact; the
   * newest `Number of checkpoints kept` are kept, including those of the
   * run a resumed run continues.
   *
   * Every file is checked against what was meant to be written before the
   * checkpoint counts as complete (deal.II's files against each other, see
   * CheckpointFiles::check_grid_files(); the state and the manifest
   * against their bytes), so a write that failed unnoticed (a full disk)
   * stops the run instead of leaving a checkpoint that cannot be resumed.
   * The last file written, `manifest`, lists every file of the checkpoint
   * with its size and checksum (64-bit FNV-1a) and a fingerprint of the run
   * (dimension, grid, materials, grains and their material points). A run
   * resumes only from a checkpoint whose files match their manifest and
   * each other, and whose fingerprint is its own: a truncated, corrupted or
   * incomplete checkpoint, or one of another parameter file, is refused
   * with a message that says what differs.
   */
  template <int dim>
  class CheckpointManager
  {
  public:
    CheckpointManager(const CheckpointParameters &parameters,
                      const std::string          &output_directory,
                      const MPI_Comm              communicator);

    /**
     * Whether the run resumes from a checkpoint (`Resume from`). If so, the
     * constructor has checked its files against the manifest and opened its
     * state: read it with read_state().
     */
    bool
    resuming() const
    {
      return resume_state != nullptr;
    }

    /**
     * The output directory of the run that wrote the checkpoint this run
     * resumes from (the directory that holds it), if that is not this
     * run's output directory; otherwise empty. A run resumed elsewhere
     * starts its histories from copies of that run's (cut back to the
     * checkpoint), and its .pvd records point to that run's files.
     */
    std::string
    resume_source() const;

    /**
     * Replace the material points of @p particle_handler and the cells of
     * @p grid by those of the checkpoint the run resumes from, after
     * checking that it was written by a run with the @p fingerprint of this
     * one (see Simulator::fingerprint()). Collective.
     */
    void
    load(const std::string               &fingerprint,
         BackgroundGrid<dim>             &grid,
         Particles::ParticleHandler<dim> &particle_handler) const;

    /**
     * What rescale_masses() changed: the factor of the deformable points'
     * masses (1 if none changed) and the change of their kinetic energy
     * and momentum (summed over all ranks).
     */
    struct MassChange
    {
      double         factor  = 1.;
      double         kinetic = 0.;
      Tensor<1, dim> momentum;
    };

    /**
     * After load(): give every material point of @p particle_handler the
     * mass density times initial volume of this run's materials
     * (@p parameters, after Parameters::apply_mass_scaling()) and grains
     * @p grains. A run resumed with another `Time stepping/Mass scaling`
     * than its checkpoint's so gets the masses of its own scaling;
     * otherwise nothing changes (the product is the one the points were
     * made with). A deformable point's velocity is kept, or with
     * `Checkpoint/Scale velocities with the mass` divided by the square
     * root of its mass ratio, so that it keeps its kinetic energy.
     * Collective.
     */
    static MassChange
    rescale_masses(const Parameters<dim>             &parameters,
                   const std::vector<GrainInfo<dim>> &grains,
                   Particles::ParticleHandler<dim>   &particle_handler,
                   const MPI_Comm                     communicator);

    /**
     * Run @p read on the state archive of the checkpoint the run resumes
     * from, turning a failed read into an InputError naming the checkpoint.
     */
    void
    read_state(
      const std::function<void(boost::archive::binary_iarchive &)> &read);

    /** Close the checkpoint the run resumed from. */
    void
    finish_resume();

    /**
     * Write checkpoint-@p step: @p grid with the material points of
     * @p particle_handler, the state written by @p write_state on rank 0,
     * and the manifest with @p fingerprint. Refuses (InputError on every
     * rank) if the file system has less free space than the checkpoint
     * needs, and stops if a write fails; in both cases the older
     * checkpoints are left intact. Collective.
     */
    void
    write(const unsigned int               step,
          const std::string               &fingerprint,
          const BackgroundGrid<dim>       &grid,
          Particles::ParticleHandler<dim> &particle_handler,
          const std::function<void(boost::archive::binary_oarchive &)>
            &write_state);

    /**
     * What a checkpoint must have been written by to be resumed by a run
     * with @p parameters and @p grains: the dimension, the grid, the
     * materials' models, the grains with their materials and material
     * points at creation. One item per line.
     */
    static std::string
    fingerprint(const Parameters<dim>             &parameters,
                const std::vector<GrainInfo<dim>> &grains);

  private:
    /**
     * Make the empty directory @p temporary_name and check that the file
     * system has room for the checkpoint. Returns what failed, or an empty
     * string (rank 0).
     */
    std::string
    prepare_directory(
      const std::string                     &temporary_name,
      const Particles::ParticleHandler<dim> &particle_handler) const;

    /**
     * Save the cells of @p grid with the material points of
     * @p particle_handler into @p temporary_name, and check on rank 0 that
     * the files hold what was meant to be written. Returns what failed, or
     * an empty string. Collective.
     */
    std::string
    write_grid(const std::string               &temporary_name,
               const BackgroundGrid<dim>       &grid,
               Particles::ParticleHandler<dim> &particle_handler) const;

    /**
     * Write the state (@p write_state) and then the manifest with
     * @p fingerprint into @p temporary_name, each checked against what was
     * meant to be written. Returns what failed, or an empty string (rank
     * 0).
     */
    std::string
    write_state_and_manifest(
      const std::string &temporary_name,
      const std::string &fingerprint,
      const std::function<void(boost::archive::binary_oarchive &)>
        &write_state);

    /**
     * Rename the complete checkpoint @p temporary_name to @p final_name and
     * delete the oldest ones beyond `Number of checkpoints kept` (rank 0).
     * Returns what failed, or an empty string.
     */
    std::string
    replace_and_prune(const std::string &temporary_name,
                      const std::string &final_name);

    const CheckpointParameters &parameters;
    const std::string           directory;
    const MPI_Comm              communicator;

    std::ifstream                                    resume_stream;
    std::unique_ptr<boost::archive::binary_iarchive> resume_state;
    /** The fingerprint in the manifest of the checkpoint resumed (rank 0). */
    std::string resume_fingerprint;
    /** The checkpoints kept, oldest first (rank 0). */
    std::vector<std::string> checkpoints;
    /** The size in bytes of the last checkpoint written (rank 0). */
    std::uintmax_t last_size = 0;
  };
} // namespace grainmpm

#endif
