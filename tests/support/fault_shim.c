/* Write faults for the tests, without mounting anything or root: loaded with LD_PRELOAD
 * into the real `stengmc` binary, it acts on writes to some files:
 *  - a full disk: writes fail with ENOSPC once a byte budget is spent, as write(2) does on
 *    a full filesystem (a short write, then -1/ENOSPC);
 *  - a stall: the first write creates a marker file and then waits, so a test can kill the
 *    process while it is writing its output.
 *
 *   STENGMC_FAULT_PATH_CONTAINS    files whose absolute path contains this text are affected
 *                                  (e.g. a scratch folder)
 *   STENGMC_FAULT_EXEMPT_CONTAINS  ... unless it contains this text (e.g. "journal": the
 *                                  journal has room, the output does not)
 *   STENGMC_FAULT_FREE_BYTES       bytes those files may still take, all together (0: the
 *                                  disk is already full; unset: no limit)
 *   STENGMC_FAULT_STALL_MARKER     path of the marker file the first write creates before
 *                                  it waits (for a signal) instead of writing
 *
 * Every write entry point the program and libhdf5 reach through the PLT is covered: write,
 * pwrite, pwrite64, writev, pwritev (HDF5's sec2 driver uses pwrite; the journal pwrite).
 * Files are recognised when opened (open, open64, openat, openat64, creat, creat64) and
 * forgotten when closed. A real small tmpfs does the same (scripts/fault_table.sh uses one
 * when it may mount); this shim makes the tests portable to a CI machine without root. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdint.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/syscall.h>
#include <sys/uio.h>
#include <unistd.h>

#define TRACKED_FDS 4096

static char affected[TRACKED_FDS];
static pthread_mutex_t budget_lock = PTHREAD_MUTEX_INITIALIZER;
static long long budget = -1; /* -1: not read yet */

static long long free_bytes(void) {
  if (budget < 0) {
    const char* text = getenv("STENGMC_FAULT_FREE_BYTES");
    budget = text ? atoll(text) : LLONG_MAX;
  }
  return budget;
}

/* True when `path` (relative to `dirfd` or the working folder) is on the full disk. */
static int matches(int dirfd, const char* path) {
  const char* pattern = getenv("STENGMC_FAULT_PATH_CONTAINS");
  if (!pattern || !*pattern || !path) return 0;
  char full[PATH_MAX * 2];
  if (path[0] == '/') {
    strncpy(full, path, sizeof full - 1);
    full[sizeof full - 1] = 0;
  } else {
    char folder[PATH_MAX] = "";
    if (dirfd == AT_FDCWD) {
      if (!getcwd(folder, sizeof folder)) folder[0] = 0;
    } else {
      char link[64];
      snprintf(link, sizeof link, "/proc/self/fd/%d", dirfd);
      const ssize_t n = readlink(link, folder, sizeof folder - 1);
      folder[n > 0 ? n : 0] = 0;
    }
    snprintf(full, sizeof full, "%s/%s", folder, path);
  }
  const char* exempt = getenv("STENGMC_FAULT_EXEMPT_CONTAINS");
  if (exempt && *exempt && strstr(full, exempt)) return 0;
  return strstr(full, pattern) != NULL;
}

static void remember(int fd, int dirfd, const char* path) {
  if (fd >= 0 && fd < TRACKED_FDS) affected[fd] = (char)matches(dirfd, path);
}

/* Through an integer: ISO C has no object-to-function pointer conversion (-Wpedantic), POSIX
   guarantees dlsym's result converts. */
#define NEXT(name) ((name##_fn)(uintptr_t)dlsym(RTLD_NEXT, #name))
typedef int (*open_fn)(const char*, int, ...);

/* With a stall marker: create it, then wait for the signal the test sends. */
static void stall_if_asked(void) {
  const char* marker = getenv("STENGMC_FAULT_STALL_MARKER");
  if (!marker || !*marker) return;
  const int fd = NEXT(open)(marker, O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd >= 0) syscall(SYS_close, fd);
  for (;;) pause();
}

/* How many of `wanted` bytes may be written to `fd`; 0 with errno = ENOSPC when none. */
static size_t allowance(int fd, size_t wanted) {
  if (fd < 0 || fd >= TRACKED_FDS || !affected[fd] || wanted == 0) return wanted;
  stall_if_asked();
  pthread_mutex_lock(&budget_lock);
  const long long left = free_bytes();
  const size_t allowed = (long long)wanted < left ? wanted : (size_t)left;
  budget = left - (long long)allowed;
  pthread_mutex_unlock(&budget_lock);
  if (allowed == 0) errno = ENOSPC;
  return allowed;
}

typedef int (*open64_fn)(const char*, int, ...);
typedef int (*openat_fn)(int, const char*, int, ...);
typedef int (*openat64_fn)(int, const char*, int, ...);
typedef int (*creat_fn)(const char*, mode_t);
typedef int (*creat64_fn)(const char*, mode_t);
typedef int (*close_fn)(int);
typedef ssize_t (*write_fn)(int, const void*, size_t);
typedef ssize_t (*pwrite_fn)(int, const void*, size_t, off_t);
typedef ssize_t (*pwrite64_fn)(int, const void*, size_t, off_t);
typedef ssize_t (*writev_fn)(int, const struct iovec*, int);
typedef ssize_t (*pwritev_fn)(int, const struct iovec*, int, off_t);

static mode_t mode_of(int flags, va_list arguments) {
  return (flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE ? (mode_t)va_arg(arguments, int) : 0;
}

int open(const char* path, int flags, ...) {
  va_list a;
  va_start(a, flags);
  const mode_t mode = mode_of(flags, a);
  va_end(a);
  const int fd = NEXT(open)(path, flags, mode);
  remember(fd, AT_FDCWD, path);
  return fd;
}

int open64(const char* path, int flags, ...) {
  va_list a;
  va_start(a, flags);
  const mode_t mode = mode_of(flags, a);
  va_end(a);
  const int fd = NEXT(open64)(path, flags, mode);
  remember(fd, AT_FDCWD, path);
  return fd;
}

int openat(int dirfd, const char* path, int flags, ...) {
  va_list a;
  va_start(a, flags);
  const mode_t mode = mode_of(flags, a);
  va_end(a);
  const int fd = NEXT(openat)(dirfd, path, flags, mode);
  remember(fd, dirfd, path);
  return fd;
}

int openat64(int dirfd, const char* path, int flags, ...) {
  va_list a;
  va_start(a, flags);
  const mode_t mode = mode_of(flags, a);
  va_end(a);
  const int fd = NEXT(openat64)(dirfd, path, flags, mode);
  remember(fd, dirfd, path);
  return fd;
}

int creat(const char* path, mode_t mode) {
  const int fd = NEXT(creat)(path, mode);
  remember(fd, AT_FDCWD, path);
  return fd;
}

int creat64(const char* path, mode_t mode) {
  const int fd = NEXT(creat64)(path, mode);
  remember(fd, AT_FDCWD, path);
  return fd;
}

int close(int fd) {
  if (fd >= 0 && fd < TRACKED_FDS) affected[fd] = 0;
  return NEXT(close)(fd);
}

ssize_t write(int fd, const void* bytes, size_t count) {
  const size_t allowed = allowance(fd, count);
  if (allowed == 0 && count > 0) return -1;
  return NEXT(write)(fd, bytes, allowed);
}

ssize_t pwrite(int fd, const void* bytes, size_t count, off_t offset) {
  const size_t allowed = allowance(fd, count);
  if (allowed == 0 && count > 0) return -1;
  return NEXT(pwrite)(fd, bytes, allowed, offset);
}

ssize_t pwrite64(int fd, const void* bytes, size_t count, off_t offset) {
  const size_t allowed = allowance(fd, count);
  if (allowed == 0 && count > 0) return -1;
  return NEXT(pwrite64)(fd, bytes, allowed, offset);
}

/* Vectored writes are cut to the first buffer: a short write is always allowed. */
ssize_t writev(int fd, const struct iovec* buffers, int count) {
  if (count > 0 && fd >= 0 && fd < TRACKED_FDS && affected[fd]) return write(fd, buffers[0].iov_base, buffers[0].iov_len);
  return NEXT(writev)(fd, buffers, count);
}

ssize_t pwritev(int fd, const struct iovec* buffers, int count, off_t offset) {
  if (count > 0 && fd >= 0 && fd < TRACKED_FDS && affected[fd])
    return pwrite(fd, buffers[0].iov_base, buffers[0].iov_len, offset);
  return NEXT(pwritev)(fd, buffers, count, offset);
}
