// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_history_file_h
#define grainmpm_postprocess_history_file_h

#include <grainmpm/base/input_error.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
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
                             "checkpoint: resume in the output directory of "
                             "the run that wrote the checkpoint.");
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
} // namespace grainmpm

#endif
