// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Test driver for runs that must fail: runs grainmpm on the given .prm and
// prints its exit code; succeeds only if grainmpm exited with code 1, so a
// test checks both the message (in .output) and the exit code.

#include <sys/wait.h>

#include <cstdlib>
#include <iostream>
#include <string>

int
main(int argc, char *argv[])
{
  if (argc != 2)
    return 2;
  const std::string command =
    std::string(GRAINMPM_EXECUTABLE) + " " + argv[1] + " 2>&1";
  std::cout << std::flush;
  const int status    = std::system(command.c_str());
  const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::cout << "exit code: " << exit_code << std::endl;
  return exit_code == 1 ? 0 : 1;
}
