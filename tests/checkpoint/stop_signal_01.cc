// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Stops at any moment leave valid files, and a stopped run goes on from its
// checkpoint to the same end. The shipped explicit two disks (3500 steps,
// output every 0.1, a checkpoint every 500 steps) run by the grainmpm
// executable:
// - SIGTERM and SIGINT once some hundred steps are done: the run finishes
//   the step, writes its output and a checkpoint, names it, and exits with
//   128 + the signal number; resumed from that checkpoint it ends with the
//   same last row of energy.csv as the uninterrupted run;
// - SIGKILL at three moments: the record files are still valid, and the
//   run resumed from its newest checkpoint ends as the uninterrupted run.
// Valid record files: particles.pvd and grid.pvd complete, every .pvtu they
// name complete and every piece it names present; energy.csv and
// grains.csv with whole rows of as many fields as their header.

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

std::string
read(const fs::path &name)
{
  std::ifstream      in(name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}



std::vector<std::string>
lines(const fs::path &name)
{
  std::ifstream            in(name);
  std::vector<std::string> result;
  for (std::string line; std::getline(in, line);)
    result.push_back(line);
  return result;
}



// The problems of an XML record file @p name: complete, and every file
// its attribute @p attribute names (relative to it) exists (and, for
// .pvtu files, is valid itself).
std::string
check_record(const fs::path &name, const std::string &attribute)
{
  const std::string text = read(name);
  if (text.find("</VTKFile>") == std::string::npos)
    return name.string() + " is incomplete; ";
  std::string      problems;
  const std::regex reference(attribute + "=\"([^\"]+)\"");
  for (std::sregex_iterator match(text.begin(), text.end(), reference), end;
       match != end;
       ++match)
    {
      const fs::path file = name.parent_path() / (*match)[1].str();
      if (!fs::exists(file))
        problems += file.string() + " is missing; ";
      else if (file.extension() == ".pvtu")
        problems += check_record(file, "Source");
    }
  return problems;
}



// The problems of the CSV history @p name: whole rows with as many fields
// as the header.
std::string
check_history(const fs::path &name)
{
  const std::string text = read(name);
  if (text.empty() || text.back() != '\n')
    return name.string() + " ends inside a row; ";
  const auto fields = [](const std::string &line) {
    return std::count(line.begin(), line.end(), ',') + 1;
  };
  const std::vector<std::string> rows = lines(name);
  for (const auto &row : rows)
    if (fields(row) != fields(rows[0]) || row.find(",,") != std::string::npos)
      return name.string() + " has a broken row; ";
  return "";
}



std::string
check_files(const fs::path &directory)
{
  const std::string problems =
    check_record(directory / "particles.pvd", "file") +
    check_record(directory / "grid.pvd", "file") +
    check_history(directory / "energy.csv") +
    check_history(directory / "grains.csv");
  return problems.empty() ? "valid" : problems;
}



// Write NAME.prm: the case with @p entries, in the directory NAME.
void
write_case(const std::string &name, const std::string &entries)
{
  std::ofstream(name + ".prm")
    << "include " GRAINMPM_SOURCE_DIR "/prm/two_disks_explicit.prm\n"
    << "subsection Output\n  set Output directory = " << name
    << "\n  set Test mode = true\nend\n"
    << "subsection Checkpoint\n  set Steps between checkpoints = 500\n"
    << "  set Replace other checkpoints = true\nend\n"
    << entries;
}



// Run grainmpm on NAME.prm (screen output in NAME.log); once energy.csv
// has @p rows rows, send @p signal. Returns the wait status.
int
run(const std::string &name, const unsigned int rows = 0, const int signal = 0)
{
  std::cout << std::flush;
  const pid_t pid = fork();
  if (pid == 0)
    {
      std::freopen((name + ".log").c_str(), "w", stdout);
      std::freopen((name + ".log").c_str(), "a", stderr);
      execl(GRAINMPM_EXECUTABLE,
            GRAINMPM_EXECUTABLE,
            (name + ".prm").c_str(),
            static_cast<char *>(nullptr));
      std::_Exit(127);
    }
  int status = 0;
  if (signal != 0)
    for (;;)
      {
        if (waitpid(pid, &status, WNOHANG) == pid)
          return status;
        if (lines(name + "/energy.csv").size() >= rows)
          {
            kill(pid, signal);
            break;
          }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
  waitpid(pid, &status, 0);
  return status;
}



std::string
describe(const int status)
{
  if (WIFEXITED(status))
    return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status))
    return "killed by signal " + std::to_string(WTERMSIG(status));
  return "?";
}



// Resume the run in @p directory from @p checkpoint; whether it ends with
// the last row of energy.csv of @p reference.
std::string
resume(const std::string &directory,
       const std::string &checkpoint,
       const std::string &reference)
{
  write_case(directory,
             "subsection Checkpoint\n  set Resume from = " + checkpoint +
               "\nend\n");
  const int status = run(directory);
  return describe(status) + ", files " + check_files(directory) +
         ", last row of energy.csv as the uninterrupted run: " +
         (lines(directory + "/energy.csv").back() == reference ? "yes" : "no");
}



int
main()
{
  std::ofstream log("output");
  for (const auto &entry : fs::directory_iterator("."))
    if (entry.path().filename().string().rfind("run-", 0) == 0)
      fs::remove_all(entry.path());

  write_case("run-reference", "");
  log << "uninterrupted: " << describe(run("run-reference")) << ", files "
      << check_files("run-reference") << std::endl;
  const std::string reference = lines("run-reference/energy.csv").back();

  for (const auto &[signal, name] :
       std::vector<std::pair<int, std::string>>{{SIGTERM, "SIGTERM"},
                                                {SIGINT, "SIGINT"}})
    {
      const std::string directory = "run-" + name;
      write_case(directory, "");
      log << name
          << " after 700 steps: " << describe(run(directory, 700, signal))
          << ", files " << check_files(directory) << std::endl;
      // The checkpoint the message names.
      std::smatch       match;
      const std::string screen = read(directory + ".log");
      if (std::regex_search(
            screen, match, std::regex("Resume from = (\\S+checkpoint-[0-9]+)")))
        log << "  resumed from the checkpoint it names: "
            << resume(directory, match[1].str(), reference) << std::endl;
      else
        log << "  names no checkpoint" << std::endl;
    }

  for (const unsigned int rows : {600, 1700, 3000})
    {
      const std::string directory = "run-SIGKILL-" + std::to_string(rows);
      write_case(directory, "");
      const int status = run(directory, rows, SIGKILL);
      log << "SIGKILL after " << rows << " rows: " << describe(status)
          << ", files " << check_files(directory) << std::endl;
      std::string newest;
      for (const auto &entry : fs::directory_iterator(directory))
        {
          const std::string file = entry.path().filename().string();
          if (file.rfind("checkpoint-", 0) == 0 &&
              file.find(".tmp") == std::string::npos &&
              entry.path().string() > newest)
            newest = entry.path().string();
        }
      log << "  resumed from the newest checkpoint: "
          << resume(directory, newest, reference) << std::endl;
    }
}
