// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_checkpoint_files_h
#define grainmpm_postprocess_checkpoint_files_h

#include <cstdint>
#include <string>
#include <utility>

namespace grainmpm
{
  /**
   * The checks of the files of a checkpoint directory (see
   * CheckpointManager), on one rank. Each function that checks returns
   * what is wrong, as the end of a sentence ("its file 'state' is
   * missing."), or an empty string.
   *
   * A checkpoint holds the files that deal.II's
   * parallel::distributed::Triangulation::save() writes for the stem
   * `grid`, a file `state` and a `manifest`:
   * - `grid`: the p4est forest; `grid.info`: a line of column names and a
   *   line "version n_ranks n_fixed n_variable n_coarse_cells" (the number
   *   of fixed-size and variable-size data attached to the cells);
   * - `grid_fixed.data`: a header of 1 + n_fixed (+ 1 if n_variable > 0)
   *   unsigned ints, the last the bytes per cell, then that many bytes for
   *   every active cell;
   * - `grid_variable.data` (if n_variable > 0): one int per active cell,
   *   the bytes of the cell's data (here its material points), then those
   *   bytes cell after cell;
   * - `state`: the run's own state (a boost binary archive);
   * - `manifest`: a header line, "file NAME SIZE CHECKSUM" per file, the
   *   fingerprint of the run between the lines "fingerprint" and "end".
   */
  namespace CheckpointFiles
  {
    /** The size of the file @p name and its 64-bit FNV-1a checksum (hex). */
    std::pair<std::uintmax_t, std::string>
    size_and_checksum(const std::string &name);

    /**
     * Write @p contents into the file @p name, then check that the file
     * holds exactly that many bytes: a write that failed (a full disk, an
     * I/O error) is reported even where the stream did not notice.
     */
    std::string
    write_verified(const std::string &name, const std::string &contents);

    /**
     * Check the files that deal.II wrote for the triangulation and the
     * material points in @p checkpoint against each other: grid.info
     * readable, the forest not empty, grid_fixed.data a whole number of
     * cells (@p n_cells of them, if not 0), grid_variable.data as long as
     * its cell sizes say.
     */
    std::string
    check_grid_files(const std::string  &checkpoint,
                     const std::uint64_t n_cells);

    /**
     * The manifest of the files in @p directory (all regular files, by
     * name) with @p fingerprint; @p total_size receives their total size.
     */
    std::string
    make_manifest(const std::string &directory,
                  const std::string &fingerprint,
                  std::uintmax_t    &total_size);

    /**
     * Check the files of @p checkpoint against its manifest and read the
     * fingerprint into @p fingerprint.
     */
    std::string
    check_manifest(const std::string &checkpoint, std::string &fingerprint);

    /**
     * The lines in which the fingerprints @p written (of a checkpoint) and
     * @p current (of this run) differ, at most three.
     */
    std::string
    fingerprint_differences(const std::string &written,
                            const std::string &current);
  } // namespace CheckpointFiles
} // namespace grainmpm

#endif
