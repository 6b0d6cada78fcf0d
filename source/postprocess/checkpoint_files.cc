// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/checkpoint_files.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <vector>

namespace grainmpm
{
  namespace CheckpointFiles
  {
    namespace
    {
      const std::string manifest_header = "grainmpm checkpoint manifest 1";

      /** The size of the file @p name, or 0 if it is not a regular file. */
      std::uintmax_t
      file_size(const std::string &name)
      {
        std::error_code code;
        if (!std::filesystem::is_regular_file(name, code))
          return 0;
        const std::uintmax_t size = std::filesystem::file_size(name, code);
        return code ? 0 : size;
      }



      /**
       * The first @p n values of type T of the file @p name; fewer if the
       * file is shorter.
       */
      template <typename T>
      std::vector<T>
      read_values(const std::string &name, const std::size_t n)
      {
        std::vector<T> values(n);
        std::ifstream  in(name, std::ios::binary);
        in.read(reinterpret_cast<char *>(values.data()), n * sizeof(T));
        values.resize(in.gcount() / sizeof(T));
        return values;
      }



      /** "its file 'NAME' has SIZE bytes where WHAT: ..." */
      std::string
      incomplete(const std::string   &name,
                 const std::uintmax_t size,
                 const std::string   &what)
      {
        return "its file '" + name + "' has " + std::to_string(size) +
               " bytes where " + what +
               ": it was not written completely (was the disk full?).";
      }
    } // namespace



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



    std::string
    write_verified(const std::string &name, const std::string &contents)
    {
      const std::string base = std::filesystem::path(name).filename().string();
      {
        std::ofstream out(name, std::ios::binary);
        out.write(contents.data(), contents.size());
        out.close();
        if (!out)
          return "the file '" + base +
                 "' could not be written completely (is the disk full?).";
      }
      const std::uintmax_t size = file_size(name);
      if (size != contents.size())
        return incomplete(base,
                          size,
                          std::to_string(contents.size()) + " were written");
      return "";
    }



    std::string
    check_grid_files(const std::string &checkpoint, const std::uint64_t n_cells)
    {
      // grid.info: the numbers of data attached to the cells.
      std::ifstream info(checkpoint + "/grid.info");
      std::string   columns;
      unsigned int  version = 0, n_ranks = 0, n_fixed = 0, n_variable = 0,
                   n_coarse = 0;
      if (!std::getline(info, columns) ||
          !(info >> version >> n_ranks >> n_fixed >> n_variable >> n_coarse))
        return "its file 'grid.info' is missing, empty or damaged.";
      if (file_size(checkpoint + "/grid") == 0)
        return "its file 'grid' (the cells) is missing or empty.";

      // grid_fixed.data: the header of cumulative sizes, then the cells.
      const std::string    fixed_name = checkpoint + "/grid_fixed.data";
      const std::uintmax_t fixed_size = file_size(fixed_name);
      const std::size_t    n_header   = 1 + n_fixed + (n_variable > 0 ? 1 : 0);
      const std::vector<unsigned int> header =
        read_values<unsigned int>(fixed_name, n_header);
      if (header.size() < n_header || header.back() == 0)
        return incomplete("grid_fixed.data",
                          fixed_size,
                          "its header needs " +
                            std::to_string(n_header * sizeof(unsigned int)));
      const std::uintmax_t header_bytes = n_header * sizeof(unsigned int);
      const std::uintmax_t cell_bytes   = header.back();
      const std::uintmax_t written_cells =
        (fixed_size - header_bytes) / cell_bytes;
      if (header_bytes + written_cells * cell_bytes != fixed_size ||
          (n_cells > 0 && written_cells != n_cells))
        return incomplete(
          "grid_fixed.data",
          fixed_size,
          std::to_string(n_cells > 0 ? n_cells : written_cells + 1) +
            " cells need " +
            std::to_string(header_bytes +
                           (n_cells > 0 ? n_cells : written_cells + 1) *
                             cell_bytes));
      if (n_variable == 0)
        return "";

      // grid_variable.data: the size of every cell's data, then the data.
      const std::string      variable_name = checkpoint + "/grid_variable.data";
      const std::uintmax_t   variable_size = file_size(variable_name);
      const std::vector<int> sizes =
        read_values<int>(variable_name, written_cells);
      if (sizes.size() < written_cells)
        return incomplete("grid_variable.data",
                          variable_size,
                          "the sizes of its " + std::to_string(written_cells) +
                            " cells need " +
                            std::to_string(written_cells * sizeof(int)));
      std::uintmax_t expected = written_cells * sizeof(int);
      for (const int size : sizes)
        {
          if (size < 0)
            return "its file 'grid_variable.data' is damaged (a cell with "
                   "negative size).";
          expected += size;
        }
      if (variable_size != expected)
        return incomplete("grid_variable.data",
                          variable_size,
                          "its cells need " + std::to_string(expected));
      return "";
    }



    std::string
    make_manifest(const std::string &directory,
                  const std::string &fingerprint,
                  std::uintmax_t    &total_size)
    {
      std::vector<std::string> files;
      for (const auto &entry : std::filesystem::directory_iterator(directory))
        if (entry.is_regular_file() &&
            entry.path().filename().string() != "manifest")
          files.push_back(entry.path().filename().string());
      std::sort(files.begin(), files.end());
      std::ostringstream out;
      out << manifest_header << '\n';
      total_size = 0;
      for (const std::string &file : files)
        {
          const auto [size, checksum] =
            size_and_checksum(directory + "/" + file);
          out << "file " << file << ' ' << size << ' ' << checksum << '\n';
          total_size += size;
        }
      out << "fingerprint\n" << fingerprint << "end\n";
      return out.str();
    }



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
  } // namespace CheckpointFiles
} // namespace grainmpm
