// LD_PRELOAD shim for the write-failure tests: the N-th write, writev, pwrite, fsync or fdatasync
// into a file below a folder fails with ENOSPC, counted over the whole run (the workbench and
// every script and ffmpeg it starts, which inherit LD_PRELOAD), as a disk that fills up would.
//
//   FAIL_WRITE_UNDER=DIR      only calls on files and folders below DIR count
//   FAIL_WRITE_COUNTER=FILE   a file of at least 4096 bytes (truncate -s 4096): the shared count
//                             (a long at offset 0) and the path whose call failed (text at 64)
//   FAIL_WRITE_AT=N           the N-th counted call fails (1-based); 0 or unset: only count
//   FAIL_WRITE_TRACE=FILE     optional: one line "N op path" per counted call appended to FILE
//
// The tests run a study once to count (and trace) its calls, then once per chosen N.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static char* shared;  // the counter file, mapped: shared by every process of the run
static long fail_at;
static const char* under;
static size_t under_length;
static int trace_fd = -1;

static ssize_t (*real_write)(int, const void*, size_t);
static ssize_t (*real_writev)(int, const struct iovec*, int);
static ssize_t (*real_pwrite)(int, const void*, size_t, off_t);
static ssize_t (*real_pwrite64)(int, const void*, size_t, off64_t);
static int (*real_fsync)(int);
static int (*real_fdatasync)(int);

__attribute__((constructor)) static void setup(void) {
  real_write = dlsym(RTLD_NEXT, "write");
  real_writev = dlsym(RTLD_NEXT, "writev");
  real_pwrite = dlsym(RTLD_NEXT, "pwrite");
  real_pwrite64 = dlsym(RTLD_NEXT, "pwrite64");
  real_fsync = dlsym(RTLD_NEXT, "fsync");
  real_fdatasync = dlsym(RTLD_NEXT, "fdatasync");
  under = getenv("FAIL_WRITE_UNDER");
  const char* counter = getenv("FAIL_WRITE_COUNTER");
  if (!under || !*under || !counter) return;
  under_length = strlen(under);
  const char* at = getenv("FAIL_WRITE_AT");
  fail_at = at ? atol(at) : 0;
  const int fd = open(counter, O_RDWR | O_CLOEXEC);
  if (fd < 0) return;
  void* map = mmap(NULL, 4096, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (map != MAP_FAILED) shared = map;
  const char* trace = getenv("FAIL_WRITE_TRACE");
  if (trace) trace_fd = open(trace, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
}

// 1 when this call is the one to fail (errno set), 0 otherwise.
static int should_fail(int fd, const char* op) {
  if (!shared) return 0;
  char link[64], path[4096];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof path - 1);
  if (n <= 0) return 0;
  path[n] = '\0';
  if (strncmp(path, under, under_length) != 0 || (path[under_length] != '/' && path[under_length] != '\0'))
    return 0;
  const long count = __atomic_add_fetch((long*)shared, 1, __ATOMIC_SEQ_CST);
  if (trace_fd >= 0) {
    char line[4200];
    const int length = snprintf(line, sizeof line, "%ld %s %s\n", count, op, path);
    if (length > 0) real_write(trace_fd, line, (size_t)length);
  }
  if (count != fail_at) return 0;
  const size_t length = strlen(path) < 4096 - 65 ? strlen(path) : 4096 - 65;
  memcpy(shared + 64, path, length);
  shared[64 + length] = '\0';
  errno = ENOSPC;
  return 1;
}

ssize_t write(int fd, const void* data, size_t size) {
  return should_fail(fd, "write") ? -1 : real_write(fd, data, size);
}
ssize_t writev(int fd, const struct iovec* iov, int count) {
  return should_fail(fd, "write") ? -1 : real_writev(fd, iov, count);
}
ssize_t pwrite(int fd, const void* data, size_t size, off_t offset) {
  return should_fail(fd, "write") ? -1 : real_pwrite(fd, data, size, offset);
}
ssize_t pwrite64(int fd, const void* data, size_t size, off64_t offset) {
  return should_fail(fd, "write") ? -1 : real_pwrite64(fd, data, size, offset);
}
int fsync(int fd) { return should_fail(fd, "fsync") ? -1 : real_fsync(fd); }
int fdatasync(int fd) { return should_fail(fd, "fsync") ? -1 : real_fdatasync(fd); }
