// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/checkpoint_files.h>
#include <grainmpm/postprocess/checkpoint_manager.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  CheckpointManager<dim>::CheckpointManager(
    const CheckpointParameters &parameters,
    const std::string          &output_directory,
    const MPI_Comm              communicator)
    : parameters(parameters)
    , directory(output_directory)
    , communicator(communicator)
  {
    const std::string &resume = parameters.resume_from;
    if (!resume.empty())
      {
        // Rank 0 checks every file against the manifest before any rank
        // reads one.
        std::string error;
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          {
            if (!std::filesystem::is_directory(resume))
              error = "there is no such directory.";
            else if (!std::filesystem::exists(resume + "/state") &&
                     !std::filesystem::exists(resume + "/manifest"))
              error = "there is no checkpoint (files state, manifest) in "
                      "this directory.";
            else
              error =
                CheckpointFiles::check_manifest(resume, resume_fingerprint);
            // The files can match a manifest written after a write that
            // failed unnoticed: check them against each other as well.
            if (error.empty())
              error = CheckpointFiles::check_grid_files(resume, 0);
            if (!error.empty())
              error = InputError("Checkpoint/Resume from = " + resume,
                                 "this checkpoint cannot be used: " + error +
                                   " Resume from another checkpoint.")
                        .what();
          }
        throw_on_all_ranks(error, communicator);

        resume_stream.open(resume + "/state", std::ios::binary);
        read_state([this](boost::archive::binary_iarchive &) {});
      }

    // Checkpoints already in the output directory: a resumed run continues
    // the list of the run it resumes (they count towards the ones kept); a
    // fresh run that writes checkpoints does not touch another run's
    // unless told to.
    std::string error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
        std::filesystem::is_directory(directory))
      {
        std::vector<std::string> found;
        for (const auto &entry : std::filesystem::directory_iterator(directory))
          {
            const std::string name = entry.path().filename().string();
            if (entry.is_directory() && name.rfind("checkpoint-", 0) == 0 &&
                name.find(".tmp") == std::string::npos)
              found.push_back(entry.path().string());
          }
        std::sort(found.begin(), found.end());
        const bool writes =
          parameters.steps_between > 0 || parameters.minutes_between > 0.;
        if (!resume.empty())
          checkpoints = found;
        else if (writes && !found.empty() &&
                 !parameters.replace_other_checkpoints)
          error =
            InputError("Checkpoint/Replace other checkpoints = false",
                       "the output directory '" + directory + "' holds " +
                         std::to_string(found.size()) +
                         " checkpoint(s) of another run (the newest is '" +
                         found.back() +
                         "'), which this run's checkpoints would replace or "
                         "delete. Resume from one of them (Checkpoint/Resume "
                         "from), choose another Output/Output directory, or "
                         "set Replace other checkpoints = true.")
              .what();
      }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  void
  CheckpointManager<dim>::read_state(
    const std::function<void(boost::archive::binary_iarchive &)> &read)
  {
    // The files match their manifest, so this fails only for a checkpoint
    // of another version of grainmpm.
    std::string error;
    try
      {
        if (resume_state == nullptr)
          resume_state =
            std::make_unique<boost::archive::binary_iarchive>(resume_stream);
        read(*resume_state);
      }
    catch (const std::exception &exception)
      {
        error = InputError("Checkpoint/Resume from = " + parameters.resume_from,
                           std::string("the state of this checkpoint cannot "
                                       "be read (") +
                             exception.what() +
                             "): it was written by another version of "
                             "grainmpm. Resume from another checkpoint.")
                  .what();
      }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  void
  CheckpointManager<dim>::load(
    const std::string               &fingerprint,
    BackgroundGrid<dim>             &grid,
    Particles::ParticleHandler<dim> &particle_handler) const
  {
    std::string error;
    // The first line names the properties a material point carries: a
    // checkpoint with others cannot be read into this version's points.
    const std::string layout_line =
      fingerprint.substr(0, fingerprint.find('\n'));
    if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
        resume_fingerprint.compare(0,
                                   layout_line.size() + 1,
                                   layout_line + '\n') != 0)
      error = InputError("Checkpoint/Resume from = " + parameters.resume_from,
                         "this checkpoint was written by an older version of "
                         "grainmpm, whose material points carry other "
                         "properties than this version's ('" +
                           layout_line +
                           "'); it cannot be resumed by this version. Resume "
                           "it with the version that wrote it, or start the "
                           "run again.")
                .what();
    else if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
             fingerprint != resume_fingerprint)
      error =
        InputError("Checkpoint/Resume from = " + parameters.resume_from,
                   "this checkpoint was written by a run with other "
                   "parameters: " +
                     CheckpointFiles::fingerprint_differences(
                       resume_fingerprint, fingerprint) +
                     ". Resume it with the parameter file of the run that "
                     "wrote it (a copy is original.prm in that run's output "
                     "directory), changing only times, output and solver "
                     "settings.")
          .what();
    throw_on_all_ranks(error, communicator);

    // The material points of the checkpoint replace the new ones, before
    // anything else looks at the grid.
    particle_handler.clear();
    grid.load(parameters.resume_from + "/grid");
    particle_handler.deserialize();
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::resume_source() const
  {
    if (parameters.resume_from.empty())
      return "";
    std::filesystem::path checkpoint(parameters.resume_from);
    if (!checkpoint.has_filename())
      checkpoint = checkpoint.parent_path();
    std::filesystem::path source = checkpoint.parent_path();
    if (source.empty())
      source = ".";
    std::error_code             code;
    const std::filesystem::path a =
      std::filesystem::weakly_canonical(source, code);
    const std::filesystem::path b =
      std::filesystem::weakly_canonical(directory, code);
    return (a == b) ? std::string() : source.string();
  }



  template <int dim>
  void
  CheckpointManager<dim>::finish_resume()
  {
    resume_state.reset();
    resume_stream.close();
  }



  template <int dim>
  void
  CheckpointManager<dim>::write(
    const unsigned int               step,
    const std::string               &fingerprint,
    const BackgroundGrid<dim>       &grid,
    Particles::ParticleHandler<dim> &particle_handler,
    const std::function<void(boost::archive::binary_oarchive &)> &write_state)
  {
    std::ostringstream name;
    name << directory << "/checkpoint-" << std::setw(6) << std::setfill('0')
         << step;
    const std::string final_name     = name.str();
    const std::string temporary_name = final_name + ".tmp";
    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    // A failure on any rank stops every rank, without the partial files;
    // the older checkpoints stay as they are.
    std::string error;
    const auto  stop_if_failed = [&]() {
      if (!error.empty())
        error = InputError("Output/Output directory = " + directory,
                           "writing the checkpoint " + final_name +
                             " failed: " + error +
                             " The older checkpoints are intact.")
                  .what();
      if (Utilities::MPI::max(error.empty() ? 0U : 1U, communicator) > 0 &&
          root)
        {
          std::error_code code;
          std::filesystem::remove_all(temporary_name, code);
        }
      throw_on_all_ranks(error, communicator);
    };

    if (root)
      error = prepare_directory(temporary_name, particle_handler);
    stop_if_failed();
    error = write_grid(temporary_name, grid, particle_handler);
    stop_if_failed();
    if (root)
      error =
        write_state_and_manifest(temporary_name, fingerprint, write_state);
    if (root && error.empty())
      error = replace_and_prune(temporary_name, final_name);
    stop_if_failed();
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::prepare_directory(
    const std::string                     &temporary_name,
    const Particles::ParticleHandler<dim> &particle_handler) const
  {
    std::error_code code;
    std::filesystem::remove_all(temporary_name, code);
    std::filesystem::create_directories(temporary_name, code);
    if (code)
      return "cannot create the directory " + temporary_name + " (" +
             code.message() + ").";
    // Enough room for it? The estimate is the size of the last checkpoint,
    // or that of the material points' data for the first one.
    const std::uintmax_t needed = std::max<std::uintmax_t>(
      last_size,
      particle_handler.n_global_particles() *
        (particle_handler.get_property_pool().n_properties_per_slot() +
         2 * dim + 2) *
        sizeof(double));
    const std::filesystem::space_info space =
      std::filesystem::space(temporary_name, code);
    if (!code && space.available < needed + needed / 10)
      return "the file system has " + std::to_string(space.available / 1024) +
             " KiB free and the checkpoint needs about " +
             std::to_string(needed / 1024) +
             " KiB (free some space, or raise Checkpoint/Steps between "
             "checkpoints).";
    return "";
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::write_grid(
    const std::string               &temporary_name,
    const BackgroundGrid<dim>       &grid,
    Particles::ParticleHandler<dim> &particle_handler) const
  {
    std::string error;
    try
      {
        particle_handler.prepare_for_serialization();
        grid.get_triangulation().save(temporary_name + "/grid");
      }
    catch (const std::exception &exception)
      {
        error = std::string("the cells and material points could not be "
                            "written (") +
                exception.what() + ").";
      }
    // deal.II does not notice every failed write: check what is on disk
    // against what was meant to be written.
    const std::uint64_t n_cells =
      grid.get_triangulation().n_global_active_cells();
    if (error.empty() && Utilities::MPI::this_mpi_process(communicator) == 0)
      error = CheckpointFiles::check_grid_files(temporary_name, n_cells);
    return error;
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::write_state_and_manifest(
    const std::string &temporary_name,
    const std::string &fingerprint,
    const std::function<void(boost::archive::binary_oarchive &)> &write_state)
  {
    std::ostringstream state;
    try
      {
        boost::archive::binary_oarchive archive(state);
        write_state(archive);
      }
    catch (const std::exception &exception)
      {
        return std::string("the state of the run could not be serialized (") +
               exception.what() + ").";
      }
    if (const std::string error =
          CheckpointFiles::write_verified(temporary_name + "/state",
                                          state.str());
        !error.empty())
      return error;
    // The manifest last: the files, their sizes and checksums, and the
    // fingerprint of the run.
    const std::string manifest =
      CheckpointFiles::make_manifest(temporary_name, fingerprint, last_size);
    return CheckpointFiles::write_verified(temporary_name + "/manifest",
                                           manifest);
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::replace_and_prune(const std::string &temporary_name,
                                            const std::string &final_name)
  {
    std::error_code code;
    std::filesystem::remove_all(final_name, code);
    std::filesystem::rename(temporary_name, final_name, code);
    if (code)
      return "renaming " + temporary_name + " failed (" + code.message() + ").";
    checkpoints.erase(std::remove(checkpoints.begin(),
                                  checkpoints.end(),
                                  final_name),
                      checkpoints.end());
    checkpoints.push_back(final_name);
    while (checkpoints.size() > parameters.n_kept)
      {
        std::filesystem::remove_all(checkpoints.front(), code);
        checkpoints.erase(checkpoints.begin());
      }
    return "";
  }



  template <int dim>
  typename CheckpointManager<dim>::MassChange
  CheckpointManager<dim>::rescale_masses(
    const Parameters<dim>             &parameters,
    const std::vector<GrainInfo<dim>> &grains,
    Particles::ParticleHandler<dim>   &particle_handler,
    const MPI_Comm                     communicator)
  {
    using Layout = MaterialPointLayout<dim>;
    MassChange change;
    double     factor = 0.;
    for (auto &particle : particle_handler)
      {
        auto               properties = particle.get_properties();
        const unsigned int grain      = Layout::get_grain(properties);
        const double       mass =
          parameters.materials[grains[grain].material].density *
          properties[Layout::initial_volume];
        const double old_mass = properties[Layout::mass];
        if (mass == old_mass)
          continue;
        if (!grains[grain].rigid && old_mass > 0.)
          {
            // Kept, or slower by the square root of the ratio so that the
            // point keeps its kinetic energy (a vibration of the same
            // amplitude, slower as the scaled wave speed).
            const Tensor<1, dim> velocity = Layout::get_velocity(properties);
            const Tensor<1, dim> scaled =
              parameters.checkpoint.scale_velocities_with_mass ?
                std::sqrt(old_mass / mass) * velocity :
                velocity;
            Layout::set_velocity(scaled, properties);
            change.kinetic += 0.5 * (mass * scaled.norm_square() -
                                     old_mass * velocity.norm_square());
            change.momentum += mass * scaled - old_mass * velocity;
            factor = mass / old_mass;
          }
        properties[Layout::mass] = mass;
      }
    change.kinetic  = Utilities::MPI::sum(change.kinetic, communicator);
    change.momentum = Utilities::MPI::sum(change.momentum, communicator);
    factor          = Utilities::MPI::max(factor, communicator);
    change.factor   = factor > 0. ? factor : 1.;
    return change;
  }



  template <int dim>
  std::string
  CheckpointManager<dim>::fingerprint(const Parameters<dim> &parameters,
                                      const std::vector<GrainInfo<dim>> &grains)
  {
    std::ostringstream out;
    out << std::setprecision(17) << "material point properties: "
        << MaterialPointLayout<dim>::n_properties
        << " (with the acceleration of the last step)\n"
        << "dimension: " << dim << '\n'
        << "grid: " << parameters.grid.lower_corner << " to "
        << parameters.grid.upper_corner << ", cells";
    for (const unsigned int n : parameters.grid.n_cells)
      out << ' ' << n;
    out << '\n' << "materials: " << parameters.materials.size() << '\n';
    // The density of the material, not the one Mass scaling makes of it:
    // a run may resume with another scaling (rescale_masses()).
    for (const auto &material : parameters.materials)
      {
        out << "material " << material.name << ": "
            << material.constitutive_model << ", density "
            << material.density / parameters.time_stepping.mass_scaling
            << ", Young's modulus " << material.youngs_modulus
            << ", Poisson's ratio " << material.poissons_ratio
            << ", hypoelastic stress " << material.hypoelastic_stress;
        out << material.get_model_parameters().fingerprint() << '\n';
      }
    out << "grains: " << grains.size() << '\n';
    types::particle_index n_points = 0;
    for (unsigned int g = 0; g < grains.size(); ++g)
      {
        out << "grain " << g + 1 << ": "
            << parameters.materials[grains[g].material].name << ", "
            << (grains[g].rigid ? "rigid" : "deformable") << ", "
            << grains[g].n_particles << " material points\n";
        n_points += grains[g].n_particles;
      }
    out << "material points: " << n_points << '\n';
    return out.str();
  }



  template class CheckpointManager<2>;
  template class CheckpointManager<3>;
} // namespace grainmpm
