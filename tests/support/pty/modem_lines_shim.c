/*
 * LD_PRELOAD shim that gives Linux pseudo-terminal slaves the modem control lines they lack.
 *
 * Why: libserialport's sp_open() reads the modem lines (ioctl TIOCMGET) while reading the
 * port's configuration, and sp_set_config()/sp_set_dtr() set them (TIOCMBIS/TIOCMBIC). A pty
 * slave answers those ioctls with an error, so libserialport refuses to open it (libserialport
 * 0.1.1, serialport.c: get_config() "TIOCMGET ioctl failed"). Under this shim the four
 * modem-line requests on a pty slave (Unix98 majors 136..143) succeed:
 *   TIOCMGET  returns the stored DTR/RTS plus CTS, DSR and CD asserted (a device is attached);
 *   TIOCMSET, TIOCMBIS, TIOCMBIC change the stored DTR/RTS.
 * Every other request and every other descriptor goes to the real ioctl unchanged.
 *
 * Where the lines live: when SLAMMTT_PTY_STATE_DIR is set (tests/support/pty/pty-run sets it),
 * in the file "$SLAMMTT_PTY_STATE_DIR/pts-<N>" as a decimal bit mask (TIOCM_DTR, TIOCM_RTS),
 * replaced atomically on every change. Every process of the test shares them, so an emulator
 * on the master side can observe the DTR line the driver sets (RPLIDAR A2 motor enable). A pty
 * with no file yet has DTR and RTS asserted, as a real port has right after open(). Without the
 * variable the lines are kept in this process only.
 *
 * This is test infrastructure: it never touches a real serial port (those have other majors).
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

/* Unix98 pty slaves: majors 136..143 (Documentation/admin-guide/devices.txt). */
enum { kPtySlaveMajorFirst = 136, kPtySlaveMajorLast = 143, kLocalSlots = 64 };

typedef int (*IoctlFunction)(int, unsigned long, ...);

static const int kOutputLines = TIOCM_DTR | TIOCM_RTS;
static const int kInputLines = TIOCM_CTS | TIOCM_DSR | TIOCM_CAR;

/* Lines of ptys of this process when no state directory is shared: index by pty number. */
static struct {
  int pty_number;
  int lines;
} local_lines[kLocalSlots];
static int local_count = 0;

static IoctlFunction RealIoctl(void) {
  static IoctlFunction real = NULL;
  if (real == NULL) {
    /* POSIX guarantees the object-to-function pointer conversion dlsym() needs; ISO C does not,
       hence the copy. */
    void* symbol = dlsym(RTLD_NEXT, "ioctl");
    memcpy(&real, &symbol, sizeof real);
  }
  return real;
}

/* The pty number N of /dev/pts/N behind `fd`, or -1 when `fd` is not a pty slave. */
static int PtySlaveNumber(int fd) {
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode)) return -1;
  const unsigned int major_number = major(st.st_rdev);
  if (major_number < kPtySlaveMajorFirst || major_number > kPtySlaveMajorLast) return -1;
  return (int)((major_number - kPtySlaveMajorFirst) * 256u + minor(st.st_rdev));
}

static const char* StateDir(void) {
  const char* dir = getenv("SLAMMTT_PTY_STATE_DIR");
  return (dir != NULL && dir[0] != '\0') ? dir : NULL;
}

static int LoadLines(int pty_number) {
  const char* dir = StateDir();
  if (dir == NULL) {
    for (int i = 0; i < local_count; ++i) {
      if (local_lines[i].pty_number == pty_number) return local_lines[i].lines;
    }
    return kOutputLines;
  }
  char path[4096];
  snprintf(path, sizeof(path), "%s/pts-%d", dir, pty_number);
  FILE* file = fopen(path, "r");
  if (file == NULL) return kOutputLines;
  int lines = kOutputLines;
  if (fscanf(file, "%d", &lines) != 1) lines = kOutputLines;
  fclose(file);
  return lines & kOutputLines;
}

static int StoreLines(int pty_number, int lines) {
  lines &= kOutputLines;
  const char* dir = StateDir();
  if (dir == NULL) {
    for (int i = 0; i < local_count; ++i) {
      if (local_lines[i].pty_number == pty_number) {
        local_lines[i].lines = lines;
        return 0;
      }
    }
    if (local_count == kLocalSlots) {
      errno = ENOMEM;
      return -1;
    }
    local_lines[local_count].pty_number = pty_number;
    local_lines[local_count].lines = lines;
    ++local_count;
    return 0;
  }
  char path[4096];
  char temporary[4200];
  snprintf(path, sizeof(path), "%s/pts-%d", dir, pty_number);
  snprintf(temporary, sizeof(temporary), "%s.%ld.tmp", path, (long)getpid());
  FILE* file = fopen(temporary, "w");
  if (file == NULL) return -1;
  const int printed = fprintf(file, "%d\n", lines);
  if (fclose(file) != 0 || printed < 0) {
    unlink(temporary);
    errno = EIO;
    return -1;
  }
  return rename(temporary, path);
}

static int IsModemLineRequest(unsigned long request) {
  return request == TIOCMGET || request == TIOCMSET || request == TIOCMBIS ||
         request == TIOCMBIC;
}

int ioctl(int fd, unsigned long request, ...) {
  va_list arguments;
  va_start(arguments, request);
  void* argument = va_arg(arguments, void*);
  va_end(arguments);

  IoctlFunction real = RealIoctl();
  if (!IsModemLineRequest(request)) {
    if (real == NULL) {
      errno = ENOSYS;
      return -1;
    }
    return real(fd, request, argument);
  }
  const int pty_number = PtySlaveNumber(fd);
  if (pty_number < 0) {
    if (real == NULL) {
      errno = ENOSYS;
      return -1;
    }
    return real(fd, request, argument);
  }
  int* bits = (int*)argument;
  if (bits == NULL) {
    errno = EFAULT;
    return -1;
  }
  const int lines = LoadLines(pty_number);
  switch (request) {
    case TIOCMGET:
      *bits = lines | kInputLines;
      return 0;
    case TIOCMSET:
      return StoreLines(pty_number, *bits);
    case TIOCMBIS:
      return StoreLines(pty_number, lines | *bits);
    case TIOCMBIC:
      return StoreLines(pty_number, lines & ~*bits);
    default:
      errno = EINVAL;
      return -1;
  }
}
