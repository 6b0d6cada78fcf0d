// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_history_file_h
#define grainmpm_postprocess_history_file_h

#include <grainmpm/base/input_error.h>

#include <deal.II/base/mpi.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace grainmpm
{
  /**
   * Open the CSV history @p filename for writing. A fresh run
   * (@p resume_length = 0) truncates it and returns true: the caller writes
   * the header. A resumed run cuts the file back to @p resume_length bytes,
   * its length at the checkpoint, and appends (returns false).
   */
  inline bool
  open_history_file(std::ofstream       &file,
                    const std::string   &filename,
                    const std::uintmax_t resume_length)
  {
    if (resume_length > 0)
      {
        if (!std::filesystem::exists(filename) ||
            std::filesystem::file_size(filename) < resume_length)
          throw InputError("Checkpoint/Resume from",
                           "the file '" + filename +
                             "' is missing or shorter than at the "
                             "checkpoint, so it is not the history of the run "
                             "that wrote the checkpoint: resume in an output "
                             "directory that holds that history, or in one "
                             "without this file (it is then copied from the "
                             "directory of the checkpoint).");
        std::filesystem::resize_file(filename, resume_length);
        file.open(filename, std::ios::app);
      }
    else
      file.open(filename);
    if (!file)
      throw InputError("Output/Output directory",
                       "cannot write the file '" + filename + "'.");
    return resume_length == 0;
  }



  /**
   * A run resumed in another output directory than the one its checkpoint
   * is in: start the history @p destination as a copy of the checkpoint
   * run's @p source, unless @p destination exists; open_history_file()
   * then cuts it back to its length at the checkpoint, @p length. Nothing
   * to do for @p length 0 (a history the checkpoint run did not write).
   */
  inline void
  copy_history_file(const std::string   &source,
                    const std::string   &destination,
                    const std::uintmax_t length)
  {
    if (length == 0 || std::filesystem::exists(destination))
      return;
    if (!std::filesystem::exists(source) ||
        std::filesystem::file_size(source) < length)
      throw InputError("Checkpoint/Resume from",
                       "the file '" + source +
                         "' of the run that wrote the checkpoint is missing "
                         "or shorter than at the checkpoint, so the history "
                         "up to it cannot be continued in '" +
                         destination + "'.");
    std::error_code code;
    std::filesystem::copy_file(source, destination, code);
    if (code)
      throw InputError("Output/Output directory",
                       "cannot write the file '" + destination + "' (" +
                         code.message() + ").");
  }



  /**
   * Throw on every rank of @p communicator if a write to the history
   * @p file (open on rank 0 only) has failed, naming @p filename.
   * Collective.
   */
  inline void
  check_history_file(const std::ofstream &file,
                     const std::string   &filename,
                     const MPI_Comm       communicator)
  {
    std::string error;
    if (file.is_open() && !file)
      error = InputError("Output/Output directory",
                         "could not write '" + filename +
                           "' (disk full, or no permission?); its last row "
                           "may be incomplete.")
                .what();
    throw_on_all_ranks(error, communicator);
  }



  /**
   * open_history_file() on rank 0 of @p communicator, with
   * @p write_header() for a fresh file, then check_history_file(): an
   * error stops every rank. Collective.
   */
  template <typename WriteHeader>
  inline void
  open_history(std::ofstream       &file,
               const std::string   &filename,
               const std::uintmax_t resume_length,
               const MPI_Comm       communicator,
               WriteHeader        &&write_header)
  {
    std::string error;
    if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          if (open_history_file(file, filename, resume_length))
            write_header();
        }
      catch (const InputError &exception)
        {
          error = exception.what();
        }
    throw_on_all_ranks(error, communicator);
    check_history_file(file, filename, communicator);
  }



  /**
   * A CSV history of a run (energy.csv, grains.csv, walls.csv,
   * contacts.csv): open on rank 0 only, cut back to its length at the
   * checkpoint when a run resumes, its write errors raised on every rank.
   */
  class HistoryFile
  {
  public:
    HistoryFile(const std::string &filename, const MPI_Comm communicator)
      : filename(filename)
      , communicator(communicator)
    {}

    /**
     * Open the file (open_history()); @p write_header(stream) writes the
     * header of a fresh file. Collective.
     */
    template <typename WriteHeader>
    void
    open(const std::uintmax_t resume_length, WriteHeader &&write_header)
    {
      open_history(file, filename, resume_length, communicator, [&]() {
        write_header(file);
        file << std::flush;
      });
    }

    /** Whether this rank writes the file (rank 0). */
    bool
    is_open() const
    {
      return file.is_open();
    }

    /** The stream of rank 0, for rows written piece by piece. */
    std::ofstream &
    stream()
    {
      return file;
    }

    /** Append @p text in one write, flushed (rank 0; nothing elsewhere). */
    void
    append(const std::string &text)
    {
      if (!file.is_open())
        return;
      file.write(text.data(), text.size());
      file.flush();
    }

    /** The length of the file so far (for a checkpoint; 0 off rank 0). */
    std::uintmax_t
    length()
    {
      if (!file.is_open())
        return 0;
      file.flush();
      return std::filesystem::file_size(filename);
    }

    /**
     * Stop every rank with a message naming the file if a write has failed
     * (a full disk), after cutting the file back to its last complete row,
     * so that no row is left half written. Collective.
     */
    void
    check_written() const
    {
      std::string error;
      if (file.is_open() && !file)
        {
          file.close();
          std::uintmax_t length = 0;
          {
            std::ifstream     in(filename, std::ios::binary);
            const std::string text((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
            const std::size_t last = text.rfind('\n');
            if (last != std::string::npos)
              length = last + 1;
          }
          std::error_code code;
          std::filesystem::resize_file(filename, length, code);
          error = InputError("Output/Output directory",
                             "could not write '" + filename +
                               "' (disk full, or no permission?); it ends "
                               "with the last row written whole.")
                    .what();
        }
      throw_on_all_ranks(error, communicator);
    }

  private:
    const std::string filename;
    const MPI_Comm    communicator;
    /** Closed by check_written() when a write failed. */
    mutable std::ofstream file;
  };
} // namespace grainmpm

#endif
