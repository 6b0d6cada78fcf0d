// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/postprocess/checkpoint_manager.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    const std::string manifest_header = "grainmpm checkpoint manifest 1";



    /** The size of the file @p name and its 64-bit FNV-1a checksum (hex). */
    std::pair<std::uintmax_t, std::string>
    size_and_checksum(const std::string &name)
    {
      std::ifstream     in(name, std::ios::binary);
      std::uint64_t     hash = 14695981039346656037ULL;
      std::uintmax_t    size = 0;
      std::vector<char> buffer(1 << 20);
      while (in)
        {
          in.read(buffer.data(), buffer.size());
          const std::streamsize n = in.gcount();
          for (std::streamsize i = 0; i < n; ++i)
            {
              hash ^= static_cast<unsigned char>(buffer[i]);
              hash *= 1099511628211ULL;
            }
          size += n;
        }
      std::ostringstream hex;
      hex << std::hex << std::setw(16) << std::setfill('0') << hash;
      return {size, hex.str()};
    }



    /**
     * Check the files of the checkpoint @p checkpoint against its manifest
     * and read the fingerprint into @p fingerprint. Returns what is wrong,
     * or an empty string.
     */
    std::string
    check_manifest(const std::string &checkpoint, std::string &fingerprint)
    {
      std::ifstream in(checkpoint + "/manifest");
      std::string   line;
      if (!in)
        return "it has no manifest, so its files cannot be checked (it was "
               "written by an older grainmpm, or the manifest was deleted).";
      if (!std::getline(in, line) || line != manifest_header)
        return "its manifest does not begin with '" + manifest_header +
               "': it is damaged or not a grainmpm checkpoint.";
      while (std::getline(in, line) && line != "fingerprint")
        {
          std::istringstream words(line);
          std::string        keyword, name, checksum;
          std::uintmax_t     size = 0;
          if (!(words >> keyword >> name >> size >> checksum) ||
              keyword != "file")
            return "its manifest is damaged (the line '" + line +
                   "' is not 'file NAME SIZE CHECKSUM').";
          const std::string path = checkpoint + "/" + name;
          if (!std::filesystem::is_regular_file(path))
            return "its file '" + name + "' is missing.";
          const auto [actual_size, actual_checksum] = size_and_checksum(path);
          if (actual_size != size)
            return "its file '" + name + "' has " +
                   std::to_string(actual_size) + " bytes where " +
                   std::to_string(size) +
                   " were written: it was truncated or overwritten.";
          if (actual_checksum != checksum)
            return "its file '" + name +
                   "' differs from what was written (checksum " +
                   actual_checksum + ", written " + checksum +
                   "): it is corrupted.";
        }
      fingerprint.clear();
      bool complete = false;
      while (std::getline(in, line))
        {
          if (line == "end")
            {
              complete = true;
              break;
            }
          fingerprint += line + '\n';
        }
      if (!complete)
        return "its manifest is truncated (no 'end' line).";
      return "";
    }



    /**
     * The lines in which the fingerprints @p written (of the checkpoint) and
     * @p current (of this run) differ, at most three.
     */
    std::string
    fingerprint_differences(const std::string &written,
                            const std::string &current)
    {
      std::istringstream a(written), b(current);
      std::string        line_a, line_b, differences;
      unsigned int       n = 0;
      for (;;)
        {
          const bool more_a = static_cast<bool>(std::getline(a, line_a));
          const bool more_b = static_cast<bool>(std::getline(b, line_b));
          if (!more_a && !more_b)
            break;
          if (more_a && more_b && line_a == line_b)
            continue;
          if (n++ == 3)
            {
              differences += "; and more";
              break;
            }
          differences += std::string(n > 1 ? "; " : "") +
                         "the checkpoint has '" +
                         (more_a ? line_a : std::string("(nothing)")) +
                         "' where this run has '" +
                         (more_b ? line_b : std::string("(nothing)")) + "'";
        }
      return differences;
    }
  } // namespace



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
              error = check_manifest(resume, resume_fingerprint);
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
    if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
        fingerprint != resume_fingerprint)
      error =
        InputError("Checkpoint/Resume from = " + parameters.resume_from,
                   "this checkpoint was written by a run with other "
                   "parameters: " +
                     fingerprint_differences(resume_fingerprint, fingerprint) +
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
    const bool root   = Utilities::MPI::this_mpi_process(communicator) == 0;
    const auto failed = [&](const std::string &what) -> std::string {
      return InputError("Output/Output directory = " + directory,
                        "writing the checkpoint " + final_name + " failed: " +
                          what + ". The older checkpoints are intact.")
        .what();
    };
    // A failure on any rank stops every rank, without the partial files.
    std::string error;
    const auto  stop_if_failed = [&]() {
      if (Utilities::MPI::max(error.empty() ? 0U : 1U, communicator) > 0 &&
          root)
        {
          std::error_code code;
          std::filesystem::remove_all(temporary_name, code);
        }
      throw_on_all_ranks(error, communicator);
    };

    // Enough room for it? The estimate is the size of the last checkpoint,
    // or that of the material points' data for the first one.
    if (root)
      {
        std::error_code code;
        std::filesystem::remove_all(temporary_name, code);
        std::filesystem::create_directories(temporary_name, code);
        if (code)
          error = failed("cannot create the directory " + temporary_name +
                         " (" + code.message() + ")");
        else
          {
            const std::uintmax_t needed = std::max<std::uintmax_t>(
              last_size,
              particle_handler.n_global_particles() *
                (particle_handler.get_property_pool().n_properties_per_slot() +
                 2 * dim + 2) *
                sizeof(double));
            const std::filesystem::space_info space =
              std::filesystem::space(temporary_name, code);
            if (!code && space.available < needed + needed / 10)
              error = failed("the file system has " +
                             std::to_string(space.available / 1024) +
                             " KiB free and the checkpoint needs about " +
                             std::to_string(needed / 1024) +
                             " KiB (free some space, or raise Checkpoint/"
                             "Steps between checkpoints)");
          }
      }
    stop_if_failed();

    try
      {
        particle_handler.prepare_for_serialization();
        grid.get_triangulation().save(temporary_name + "/grid");
      }
    catch (const std::exception &exception)
      {
        error = failed(std::string("the cells and material points could not "
                                   "be written (") +
                       exception.what() + ")");
      }
    stop_if_failed();
    if (root)
      {
        std::ofstream out(temporary_name + "/state", std::ios::binary);
        {
          boost::archive::binary_oarchive archive(out);
          write_state(archive);
        }
        out.close();
        if (!out)
          error = failed("the file state could not be written completely "
                         "(is the disk full?)");
      }
    if (root && error.empty())
      {
        // The manifest last: the files, their sizes and checksums, and the
        // fingerprint of the run.
        std::vector<std::string> files;
        for (const auto &entry :
             std::filesystem::directory_iterator(temporary_name))
          if (entry.is_regular_file())
            files.push_back(entry.path().filename().string());
        std::sort(files.begin(), files.end());
        std::ofstream out(temporary_name + "/manifest");
        out << manifest_header << '\n';
        std::uintmax_t size = 0;
        for (const std::string &file : files)
          {
            const auto [file_size, checksum] =
              size_and_checksum(temporary_name + "/" + file);
            out << "file " << file << ' ' << file_size << ' ' << checksum
                << '\n';
            size += file_size;
          }
        out << "fingerprint\n" << fingerprint << "end\n";
        out.close();
        if (!out)
          error = failed("the file manifest could not be written completely "
                         "(is the disk full?)");
        last_size = size;
      }
    if (root)
      {
        std::error_code code;
        if (error.empty())
          {
            std::filesystem::remove_all(final_name, code);
            std::filesystem::rename(temporary_name, final_name, code);
            if (code)
              error = failed("renaming " + temporary_name + " failed (" +
                             code.message() + ")");
          }
        if (error.empty())
          {
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
          }
      }
    stop_if_failed();
  }



  template class CheckpointManager<2>;
  template class CheckpointManager<3>;
} // namespace grainmpm
