// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Test driver for runs that must fail: runs grainmpm on the given .prm and
// prints its exit code; succeeds only if grainmpm exited with code 1, so a
// test checks both the message (in .output) and the exit code. A line
// "# MPI ranks: N" in the .prm runs grainmpm on N ranks through mpiexec,
// a line "# Check parameters only" runs grainmpm --check-parameters;
// Open MPI's own report of the failed job (between lines of dashes, with
// process ids) is left out of the output. On several ranks mpiexec forwards
// standard output and standard error through separate channels, so their
// order is not defined; there the error stream is printed after the output.

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

int
main(int argc, char *argv[])
{
  if (argc != 2)
    return 2;
  unsigned int n_ranks    = 1;
  bool         check_only = false;
  {
    std::ifstream     prm(argv[1]);
    const std::string marker = "# MPI ranks: ";
    for (std::string line; std::getline(prm, line);)
      if (line.rfind(marker, 0) == 0)
        n_ranks = std::stoi(line.substr(marker.size()));
      else if (line == "# Check parameters only")
        check_only = true;
  }
  std::string command = std::string(GRAINMPM_EXECUTABLE) +
                        (check_only ? " --check-parameters " : " ") + argv[1];
  if (n_ranks > 1)
    command = std::string(GRAINMPM_MPIEXEC) + " -n " + std::to_string(n_ranks) +
              " --allow-run-as-root --oversubscribe " + command;
  const std::string error_file = "grainmpm_standard_error";
  command += n_ranks > 1 ? " 2>" + error_file : std::string(" 2>&1");
  std::cout << std::flush;

  FILE *pipe = popen(command.c_str(), "r");
  if (pipe == nullptr)
    return 2;
  std::string line;
  bool        in_mpi_report = false;
  for (int c = std::fgetc(pipe);; c = std::fgetc(pipe))
    {
      if (c != EOF && c != '\n')
        {
          line += static_cast<char>(c);
          continue;
        }
      if (line.rfind("------", 0) == 0)
        in_mpi_report = !in_mpi_report;
      else if (!in_mpi_report && !(c == EOF && line.empty()))
        std::cout << line << '\n';
      line.clear();
      if (c == EOF)
        break;
    }
  const int status    = pclose(pipe);
  const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (n_ranks > 1)
    {
      std::ifstream errors(error_file);
      bool          in_report = false;
      for (std::string error_line; std::getline(errors, error_line);)
        if (error_line.rfind("------", 0) == 0)
          in_report = !in_report;
        else if (!in_report)
          std::cout << error_line << '\n';
      std::remove(error_file.c_str());
    }
  std::cout << "exit code: " << exit_code << std::endl;
  return exit_code == 1 ? 0 : 1;
}
