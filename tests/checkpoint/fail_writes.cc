// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// A library for LD_PRELOAD in tests: every write to a file whose name ends
// with the text of the environment variable GRAINMPM_FAIL_WRITES_TO fails
// with ENOSPC, as on a full disk, while all other files are written
// normally; with GRAINMPM_FAIL_WRITES_AFTER=N the first N files of that
// name that the process opens are written normally. It covers what
// grainmpm and the libraries it uses (libstdc++ streams, MPI-IO) write
// through: open/openat/creat/fopen, then write/pwrite/writev/pwritev.

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <set>

namespace
{
  std::mutex    mutex;
  std::set<int> failing;
  /** How many files of the name were opened so far. */
  unsigned long n_opened = 0;

  template <typename Function>
  Function
  next(const char *name)
  {
    return reinterpret_cast<Function>(dlsym(RTLD_NEXT, name));
  }

  void
  track(const int fd, const char *path)
  {
    const char *suffix = std::getenv("GRAINMPM_FAIL_WRITES_TO");
    if (fd < 0 || path == nullptr || suffix == nullptr || *suffix == '\0')
      return;
    const std::size_t n = std::strlen(path), m = std::strlen(suffix);
    const std::lock_guard<std::mutex> lock(mutex);
    failing.erase(fd);
    if (n >= m && std::strcmp(path + n - m, suffix) == 0)
      {
        const char *after = std::getenv("GRAINMPM_FAIL_WRITES_AFTER");
        if (n_opened++ >=
            (after != nullptr ? std::strtoul(after, nullptr, 10) : 0UL))
          failing.insert(fd);
      }
  }

  bool
  fails(const int fd)
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (failing.count(fd) == 0)
      return false;
    errno = ENOSPC;
    return true;
  }

  mode_t
  mode_argument(const int flags, va_list arguments)
  {
    return (flags & (O_CREAT | O_TMPFILE)) != 0 ? va_arg(arguments, int) : 0;
  }
} // namespace

extern "C"
{
  int
  open(const char *path, int flags, ...)
  {
    va_list arguments;
    va_start(arguments, flags);
    const mode_t mode = mode_argument(flags, arguments);
    va_end(arguments);
    const int fd =
      next<int (*)(const char *, int, ...)>("open")(path, flags, mode);
    track(fd, path);
    return fd;
  }

  int
  open64(const char *path, int flags, ...)
  {
    va_list arguments;
    va_start(arguments, flags);
    const mode_t mode = mode_argument(flags, arguments);
    va_end(arguments);
    const int fd =
      next<int (*)(const char *, int, ...)>("open64")(path, flags, mode);
    track(fd, path);
    return fd;
  }

  int
  openat(int directory, const char *path, int flags, ...)
  {
    va_list arguments;
    va_start(arguments, flags);
    const mode_t mode = mode_argument(flags, arguments);
    va_end(arguments);
    const int fd = next<int (*)(int, const char *, int, ...)>(
      "openat")(directory, path, flags, mode);
    track(fd, path);
    return fd;
  }

  int
  creat(const char *path, mode_t mode)
  {
    const int fd = next<int (*)(const char *, mode_t)>("creat")(path, mode);
    track(fd, path);
    return fd;
  }

  FILE *
  fopen(const char *path, const char *mode)
  {
    FILE *file =
      next<FILE *(*)(const char *, const char *)>("fopen")(path, mode);
    if (file != nullptr)
      track(fileno(file), path);
    return file;
  }

  FILE *
  fopen64(const char *path, const char *mode)
  {
    FILE *file =
      next<FILE *(*)(const char *, const char *)>("fopen64")(path, mode);
    if (file != nullptr)
      track(fileno(file), path);
    return file;
  }

  ssize_t
  write(int fd, const void *buffer, size_t count)
  {
    if (fails(fd))
      return -1;
    return next<ssize_t (*)(int, const void *, size_t)>(
      "write")(fd, buffer, count);
  }

  ssize_t
  pwrite(int fd, const void *buffer, size_t count, off_t offset)
  {
    if (fails(fd))
      return -1;
    return next<ssize_t (*)(int, const void *, size_t, off_t)>(
      "pwrite")(fd, buffer, count, offset);
  }

  ssize_t
  pwrite64(int fd, const void *buffer, size_t count, off64_t offset)
  {
    if (fails(fd))
      return -1;
    return next<ssize_t (*)(int, const void *, size_t, off64_t)>(
      "pwrite64")(fd, buffer, count, offset);
  }

  ssize_t
  writev(int fd, const struct iovec *vectors, int count)
  {
    if (fails(fd))
      return -1;
    return next<ssize_t (*)(int, const struct iovec *, int)>(
      "writev")(fd, vectors, count);
  }

  ssize_t
  pwritev(int fd, const struct iovec *vectors, int count, off_t offset)
  {
    if (fails(fd))
      return -1;
    return next<ssize_t (*)(int, const struct iovec *, int, off_t)>(
      "pwritev")(fd, vectors, count, offset);
  }

  int
  close(int fd)
  {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      failing.erase(fd);
    }
    return next<int (*)(int)>("close")(fd);
  }
}
