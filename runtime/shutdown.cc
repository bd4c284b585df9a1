#include "runtime/shutdown.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <mutex>

namespace slammtt {
namespace {

std::atomic<int> g_requested{0};
std::atomic<int> g_signal{0};
int g_pipe[2] = {-1, -1};
std::once_flag g_pipe_once;

void MakePipe() {
  if (pipe(g_pipe) == 0) {
    for (int fd : g_pipe) {
      fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
      fcntl(fd, F_SETFD, FD_CLOEXEC);
    }
  }
}

void Wake() {
  if (g_pipe[1] >= 0) {
    const int saved_errno = errno;
    const char byte = 1;
    ssize_t ignored = write(g_pipe[1], &byte, 1);
    (void)ignored;
    errno = saved_errno;
  }
}

extern "C" void OnShutdownSignal(int signal_number) {
  g_signal = signal_number;
  g_requested = 1;
  Wake();
}

}  // namespace

void InstallShutdownHandlers() {
  std::call_once(g_pipe_once, MakePipe);
  struct sigaction action = {};
  action.sa_handler = OnShutdownSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: blocking calls return EINTR and loops re-check
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  signal(SIGPIPE, SIG_IGN);
}

bool ShutdownRequested() { return g_requested.load() != 0; }
int ShutdownSignal() { return g_signal.load(); }

void RequestShutdown() {
  std::call_once(g_pipe_once, MakePipe);
  g_requested = 1;
  Wake();
}

void ResetShutdown() {
  g_requested = 0;
  g_signal = 0;
  if (g_pipe[0] >= 0) {
    char buffer[64];
    while (read(g_pipe[0], buffer, sizeof buffer) > 0) {
    }
  }
}

int ShutdownFd() {
  std::call_once(g_pipe_once, MakePipe);
  return g_pipe[0];
}

}  // namespace slammtt
