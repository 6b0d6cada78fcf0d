// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A checkpoint is complete only when every file it needs holds what was
// meant to be written. The shipped explicit two disks to t = 0.3 with a
// checkpoint every 100 steps, run by the grainmpm executable with a library
// (fail_writes.cc, through LD_PRELOAD) that makes every write to one file of
// the second checkpoint fail with ENOSPC, as on a full disk: the material
// points (grid_variable.data, on 1 and 2 ranks), the cells'
// fixed data, the state, the manifest. Each run stops at step 200 with one
// message naming the file, leaves checkpoint-000100 as the only checkpoint
// (no checkpoint-000200, complete or not), and resumed from it ends with the
// last row of energy.csv of the uninterrupted run on as many ranks. (deal.II's
// MPI-IO writes of grid_variable.data failed unnoticed: the checkpoint was
// renamed complete with an empty data file and a resume from it crashed; a
// failed write of the state stopped the run with "std::bad_cast".)

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

std::vector<std::string>
lines(const fs::path &name)
{
  std::ifstream            in(name);
  std::vector<std::string> result;
  for (std::string line; std::getline(in, line);)
    result.push_back(line);
  return result;
}



// Write NAME.prm: the case with @p entries, in the directory NAME.
void
write_case(const std::string &name, const std::string &entries = "")
{
  std::ofstream(name + ".prm")
    << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_explicit.prm\n"
    << "subsection Time stepping\n  set End time = 0.3\nend\n"
    << "subsection Output\n  set Output directory = " << name
    << "\n  set Test mode = true\n  set Write particles = false\n"
    << "  set Write grid = false\nend\n"
    << "subsection Checkpoint\n  set Steps between checkpoints = 100\nend\n"
    << entries;
}



// Run grainmpm on NAME.prm on @p n_ranks ranks, every write to the second
// file named @p failing failing (none if empty); the exit status.
std::string
run(const std::string &name,
    const unsigned int n_ranks = 1,
    const std::string &failing = "")
{
  std::string command =
    GRAINMPM_EXECUTABLE " " + name + ".prm > " + name + ".log 2>&1";
  if (n_ranks > 1)
    command = GRAINMPM_MPIEXEC " -n " + std::to_string(n_ranks) +
              " --allow-run-as-root --oversubscribe -x LD_PRELOAD -x "
              "GRAINMPM_FAIL_WRITES_TO -x GRAINMPM_FAIL_WRITES_AFTER " +
              command;
  if (!failing.empty())
    command = "LD_PRELOAD=" GRAINMPM_FAIL_WRITES_LIBRARY
              " GRAINMPM_FAIL_WRITES_TO=" +
              failing + " GRAINMPM_FAIL_WRITES_AFTER=1 " + command;
  std::cout << std::flush;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ?
           "exit status " + std::to_string(WEXITSTATUS(status)) :
           "killed by signal " + std::to_string(WTERMSIG(status));
}



// The error message of the run NAME, with NAME for the output directory.
std::string
message(const std::string &name)
{
  for (const std::string &line : lines(name + ".log"))
    if (line.rfind("grainmpm: error: ", 0) == 0)
      return std::regex_replace(line, std::regex(name), "OUT");
  return "(none)";
}



// The checkpoints in the directory NAME, complete or not.
std::string
checkpoints(const std::string &name)
{
  std::vector<std::string> found;
  for (const auto &entry : fs::directory_iterator(name))
    if (entry.path().filename().string().rfind("checkpoint-", 0) == 0)
      found.push_back(entry.path().filename().string());
  std::sort(found.begin(), found.end());
  std::string list;
  for (const auto &name : found)
    list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "none" : list;
}



int
main()
{
  for (const auto &entry : fs::directory_iterator("."))
    if (entry.path().filename().string().rfind("fail-", 0) == 0 ||
        entry.path().filename().string().rfind("uninterrupted", 0) == 0)
      fs::remove_all(entry.path());

  // The last rows of energy.csv without faults, on 1 and 2 ranks.
  std::string reference[3];
  for (const unsigned int n_ranks : {1U, 2U})
    {
      const std::string name = "uninterrupted-" + std::to_string(n_ranks);
      write_case(name);
      std::cout << "uninterrupted (" << n_ranks
                << (n_ranks > 1 ? " ranks" : " rank")
                << "): " << run(name, n_ranks) << std::endl;
      reference[n_ranks] = lines(name + "/energy.csv").back();
    }

  const std::vector<std::pair<std::string, unsigned int>> cases = {
    {"grid_variable.data", 1},
    {"grid_variable.data", 2},
    {"grid_fixed.data", 1},
    {"state", 1},
    {"manifest", 1}};
  for (const auto &[file, n_ranks] : cases)
    {
      const std::string name = "fail-" + file.substr(0, file.find('.')) + "-" +
                               std::to_string(n_ranks);
      write_case(name);
      std::cout << file << " fails in the second checkpoint (" << n_ranks
                << (n_ranks > 1 ? " ranks" : " rank")
                << "): " << run(name, n_ranks, file) << '\n'
                << "  " << message(name) << '\n'
                << "  checkpoints left: " << checkpoints(name) << std::endl;

      const std::string resumed = name + "-resumed";
      fs::remove_all(resumed);
      fs::copy(name, resumed, fs::copy_options::recursive);
      write_case(resumed,
                 "subsection Checkpoint\n  set Resume from = " + resumed +
                   "/checkpoint-000100\nend\n");
      const std::string status = run(resumed, n_ranks);
      std::cout << "  resumed from checkpoint-000100: " << status
                << ", last row of energy.csv as the uninterrupted run: "
                << (lines(resumed + "/energy.csv").back() ==
                        reference[n_ranks] ?
                      "yes" :
                      "no")
                << std::endl;
    }
}
