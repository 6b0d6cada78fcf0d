// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/postprocess/checkpoint_manager.h>

#include <algorithm>
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
        resume_stream.open(resume + "/state", std::ios::binary);
        if (!resume_stream)
          throw InputError("Checkpoint/Resume from = " + resume,
                           "there is no checkpoint (file state) in this "
                           "directory.");
        resume_state =
          std::make_unique<boost::archive::binary_iarchive>(resume_stream);
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
  CheckpointManager<dim>::load(
    BackgroundGrid<dim>             &grid,
    Particles::ParticleHandler<dim> &particle_handler) const
  {
    // The material points of the checkpoint replace the new ones, before
    // anything else looks at the grid.
    particle_handler.clear();
    grid.load(parameters.resume_from + "/grid");
    particle_handler.deserialize();
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
    if (root)
      {
        std::filesystem::remove_all(temporary_name);
        std::filesystem::create_directories(temporary_name);
      }
    MPI_Barrier(communicator);

    particle_handler.prepare_for_serialization();
    grid.get_triangulation().save(temporary_name + "/grid");
    if (root)
      {
        std::ofstream out(temporary_name + "/state", std::ios::binary);
        boost::archive::binary_oarchive archive(out);
        write_state(archive);
      }
    MPI_Barrier(communicator);
    if (root)
      {
        std::filesystem::remove_all(final_name);
        std::filesystem::rename(temporary_name, final_name);
        checkpoints.erase(std::remove(checkpoints.begin(),
                                      checkpoints.end(),
                                      final_name),
                          checkpoints.end());
        checkpoints.push_back(final_name);
        while (checkpoints.size() > parameters.n_kept)
          {
            std::filesystem::remove_all(checkpoints.front());
            checkpoints.erase(checkpoints.begin());
          }
      }
  }



  template class CheckpointManager<2>;
  template class CheckpointManager<3>;
} // namespace grainmpm
