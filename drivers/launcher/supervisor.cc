#include "drivers/launcher/supervisor.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <sstream>
#include <stdexcept>

#include "drivers/launcher/bus_network.h"
#include "drivers/launcher/line_prefixer.h"
#include "drivers/launcher/restart_policy.h"
#include "runtime/log.h"
#include "runtime/shutdown.h"

namespace slammtt {
namespace {

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool IsExecutableFile(const std::string& path) {
  struct stat info = {};
  return stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && access(path.c_str(), X_OK) == 0;
}

void WriteAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      return;  // our own output is gone (closed terminal, EPIPE): keep supervising anyway
    }
  }
}

void MakeDirectories(const std::string& path) {
  std::string partial;
  std::stringstream parts(path);
  std::string part;
  if (!path.empty() && path[0] == '/') partial = "/";
  while (std::getline(parts, part, '/')) {
    if (part.empty()) continue;
    partial += part + "/";
    if (mkdir(partial.c_str(), 0755) != 0 && errno != EEXIST) {
      throw std::runtime_error("cannot create the log directory " + path + ": " + std::strerror(errno));
    }
  }
  struct stat info = {};
  if (stat(path.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || access(path.c_str(), W_OK) != 0) {
    throw std::runtime_error("the log directory " + path + " is not a writable directory");
  }
  // Anyone who may rename or remove files in it could swap a log for a link to another file
  // between the launcher creating it and lcm-logger opening it.
  if ((info.st_mode & S_IWOTH) != 0 && (info.st_mode & S_ISVTX) == 0) {
    throw std::runtime_error("the log directory " + path +
                             " is writable by other users (chmod o-w it, or set the sticky bit)");
  }
}

// Creates `path` as a new empty file, never through a link and never over an existing file
// (O_CREAT | O_EXCL, which also refuses a symlink of that name, dangling or not). False when
// the name is taken; throws for any other failure.
bool CreateExclusively(const std::string& path) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0640);
  if (fd >= 0) {
    close(fd);
    return true;
  }
  if (errno == EEXIST) return false;
  throw std::runtime_error("cannot create the log file " + path + ": " + std::strerror(errno));
}

// Whether an argument of `spec` expands {log_file} (a literal "{{log_file}}" does not).
bool UsesLogFile(const ProcessSpec& spec) {
  const std::string marker = "\x01";
  for (const std::string& arg : spec.args) {
    const std::string expanded = ExpandLaunchArgument(
        arg, {{"config", ""}, {"lcm_url", ""}, {"log_directory", ""}, {"log_file", marker}});
    if (expanded.find(marker) != std::string::npos) return true;
  }
  return false;
}

std::string DescribeStatus(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const char* name = strsignal(WTERMSIG(status));
    return std::string("was killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
           (name != nullptr ? name : "?") + ")";
  }
  return "ended";
}

}  // namespace

struct Supervisor::Child {
  Child(const ProcessSpec& s, std::string p, const LaunchPlan& plan, size_t width)
      : spec(s),
        path(std::move(p)),
        policy(plan, s.restart),
        out(OutputPrefix(s.name, width)),
        err(OutputPrefix(s.name, width)) {}
  ProcessSpec spec;
  std::string path;
  RestartPolicy policy;
  LinePrefixer out;
  LinePrefixer err;
  pid_t pid = -1;
  int out_fd = -1;
  int err_fd = -1;
  double started_s = 0.0;
  double restart_at_s = -1.0;  // a restart is pending at this time
  bool finished = false;       // ended for good
};

std::string SelfDirectory() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return ".";
  std::string path(buffer, static_cast<size_t>(n));
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

std::string ResolveProgram(const std::string& program, const std::string& self_directory) {
  if (program.find('/') != std::string::npos) {
    if (IsExecutableFile(program)) return program;
    throw std::runtime_error(program + ": not an executable file");
  }
  const std::string beside = self_directory + "/" + program;
  if (IsExecutableFile(beside)) return beside;
  const char* path_variable = std::getenv("PATH");
  std::stringstream directories(path_variable != nullptr ? path_variable : "/usr/bin:/bin");
  std::string directory;
  while (std::getline(directories, directory, ':')) {
    if (directory.empty()) continue;
    const std::string candidate = directory + "/" + program;
    if (IsExecutableFile(candidate)) return candidate;
  }
  throw std::runtime_error(program + ": not found next to slammtt-launch (" + self_directory +
                           ") or in PATH");
}

Supervisor::Supervisor(const LaunchPlan& plan, const SupervisorSettings& settings)
    : plan_(plan), settings_(settings) {
  size_t width = 0;
  for (const ProcessSpec& spec : plan_.processes) width = std::max(width, spec.name.size());
  for (const ProcessSpec& spec : plan_.processes) {
    std::string path;
    try {
      path = ResolveProgram(spec.program, settings_.self_directory);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("robot.processes '" + spec.name + "': " + e.what());
    }
    children_.push_back(std::make_unique<Child>(spec, path, plan_, width));
  }
}

Supervisor::~Supervisor() {
  // Run() stops everything; this only covers an exception thrown out of it.
  for (auto& child : children_) {
    if (child->pid > 0) {
      kill(-child->pid, SIGKILL);
      waitpid(child->pid, nullptr, 0);
    }
    if (child->out_fd >= 0) close(child->out_fd);
    if (child->err_fd >= 0) close(child->err_fd);
  }
}

std::string Supervisor::NextLogFile(bool create) const {
  const std::time_t now = std::time(nullptr);
  std::tm local = {};
  localtime_r(&now, &local);
  const std::string base = plan_.log_directory + "/" +
                           LogFileName(local.tm_year + 1900, local.tm_mon + 1, local.tm_mday,
                                       local.tm_hour, local.tm_min, local.tm_sec);
  std::string candidate = base;
  for (int i = 1;; ++i) {
    struct stat info = {};
    // lstat: a planted symlink, even a dangling one, takes its name.
    const bool taken =
        create ? !CreateExclusively(candidate) : lstat(candidate.c_str(), &info) == 0;
    if (!taken) return candidate;
    if (i > 10000) throw std::runtime_error("no free log file name beside " + base);
    candidate = base.substr(0, base.size() - 4) + "-" + std::to_string(i) + ".lcm";
  }
}

std::vector<std::string> Supervisor::Arguments(
    const Child& child, const std::map<std::string, std::string>& variables) const {
  std::vector<std::string> args = LaunchArguments(child.spec, settings_.config_path, variables);
  if (child.spec.pass_config && settings_.lcm_url_from_command_line) {
    args.insert(args.begin() + 2, {"--lcm-url", settings_.lcm_url});
  }
  return args;
}

std::vector<std::vector<std::string>> Supervisor::CommandLines() const {
  std::vector<std::vector<std::string>> lines;
  const std::map<std::string, std::string> variables = {
      {"config", settings_.config_path},
      {"lcm_url", settings_.lcm_url},
      {"log_directory", plan_.log_directory},
      {"log_file", NextLogFile(/*create=*/false)}};
  for (const auto& child : children_) {
    std::vector<std::string> line = {child->path};
    for (std::string& arg : Arguments(*child, variables)) line.push_back(std::move(arg));
    lines.push_back(std::move(line));
  }
  return lines;
}

void Supervisor::Start(Child* child) {
  const std::map<std::string, std::string> variables = {
      {"config", settings_.config_path},
      {"lcm_url", settings_.lcm_url},
      {"log_directory", plan_.log_directory},
      {"log_file", UsesLogFile(child->spec) ? NextLogFile(/*create=*/true) : std::string()}};
  std::vector<std::string> argv = {child->path};
  for (std::string& arg : Arguments(*child, variables)) argv.push_back(std::move(arg));
  std::vector<char*> c_argv;
  for (std::string& arg : argv) c_argv.push_back(arg.data());
  c_argv.push_back(nullptr);

  int out_pipe[2];
  int err_pipe[2];
  if (pipe2(out_pipe, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  if (pipe2(err_pipe, O_CLOEXEC) != 0) {
    close(out_pipe[0]);
    close(out_pipe[1]);
    throw std::runtime_error("pipe failed");
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]}) close(fd);
    throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // Child: only async-signal-safe calls from here to exec.
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(126);  // the launcher died before prctl
    signal(SIGPIPE, SIG_DFL);             // ignored dispositions survive exec: undo ours
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    const int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd >= 0) dup2(null_fd, 0);
    dup2(out_pipe[1], 1);
    dup2(err_pipe[1], 2);
    execv(c_argv[0], c_argv.data());
    const char message[] = "slammtt-launch: exec failed\n";
    ssize_t ignored = write(2, message, sizeof message - 1);
    (void)ignored;
    _exit(127);
  }
  setpgid(pid, pid);  // also from here, so that no signal can race the child's own call
  close(out_pipe[1]);
  close(err_pipe[1]);
  fcntl(out_pipe[0], F_SETFL, fcntl(out_pipe[0], F_GETFL) | O_NONBLOCK);
  fcntl(err_pipe[0], F_SETFL, fcntl(err_pipe[0], F_GETFL) | O_NONBLOCK);
  child->pid = pid;
  child->out_fd = out_pipe[0];
  child->err_fd = err_pipe[0];
  child->started_s = NowSeconds();
  child->restart_at_s = -1.0;
  std::string command;
  for (const std::string& arg : argv) command += (command.empty() ? "" : " ") + arg;
  LogInfo() << "started " << child->spec.name << " (pid " << pid << "): " << command;
}

void Supervisor::DrainAndClose(Child* child) {
  char buffer[4096];
  for (int* fd : {&child->out_fd, &child->err_fd}) {
    if (*fd < 0) continue;
    LinePrefixer& prefixer = fd == &child->out_fd ? child->out : child->err;
    const int target = fd == &child->out_fd ? 1 : 2;
    for (;;) {
      const ssize_t n = read(*fd, buffer, sizeof buffer);
      if (n > 0) {
        WriteAll(target, prefixer.Feed(buffer, static_cast<size_t>(n)));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      break;  // EOF, or nothing more now (a grandchild may hold the pipe: we stop listening)
    }
    WriteAll(target, prefixer.Flush());
    close(*fd);
    *fd = -1;
  }
}

void Supervisor::Pump(int timeout_ms) {
  std::vector<pollfd> fds;
  std::vector<std::pair<Child*, bool>> owners;  // child, is stdout
  fds.push_back({ShutdownFd(), POLLIN, 0});
  owners.push_back({nullptr, false});
  for (auto& child : children_) {
    if (child->out_fd >= 0) {
      fds.push_back({child->out_fd, POLLIN, 0});
      owners.push_back({child.get(), true});
    }
    if (child->err_fd >= 0) {
      fds.push_back({child->err_fd, POLLIN, 0});
      owners.push_back({child.get(), false});
    }
  }
  if (poll(fds.data(), fds.size(), timeout_ms) <= 0) return;
  char buffer[4096];
  for (size_t i = 1; i < fds.size(); ++i) {
    if (fds[i].revents == 0) continue;
    Child* child = owners[i].first;
    const bool is_out = owners[i].second;
    int& fd = is_out ? child->out_fd : child->err_fd;
    LinePrefixer& prefixer = is_out ? child->out : child->err;
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
      WriteAll(is_out ? 1 : 2, prefixer.Feed(buffer, static_cast<size_t>(n)));
    } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
      WriteAll(is_out ? 1 : 2, prefixer.Flush());
      close(fd);
      fd = -1;
    }
  }
}

void Supervisor::Reap(bool stopping) {
  for (auto& owned : children_) {
    Child* child = owned.get();
    if (child->pid <= 0) continue;
    int status = 0;
    const pid_t done = waitpid(child->pid, &status, WNOHANG);
    if (done != child->pid) continue;
    const double now = NowSeconds();
    child->pid = -1;
    DrainAndClose(child);
    const double ran_s = now - child->started_s;
    const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (stopping) {
      if (clean || (WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM)) {
        LogInfo() << child->spec.name << " stopped (" << DescribeStatus(status) << ")";
      } else {
        LogWarning() << child->spec.name << " " << DescribeStatus(status) << " while stopping";
      }
      child->finished = true;
      continue;
    }
    const RestartPolicy::Decision decision = child->policy.OnExit(child->started_s, now, clean);
    std::ostringstream what;
    what << child->spec.name << " " << DescribeStatus(status) << " after " << ran_s << " s";
    if (decision.restart) {
      child->restart_at_s = now + decision.delay_s;
      LogWarning() << what.str() << "; restarting in " << decision.delay_s << " s (restart "
                   << child->policy.restarts_in_a_row() << " of at most " << plan_.max_restarts
                   << " in a row)";
    } else if (decision.gave_up) {
      child->finished = true;
      failed_ = true;
      LogError() << what.str() << "; giving up on it after "
                 << child->policy.restarts_in_a_row() << " restarts in a row"
                 << (plan_.on_give_up == GiveUpAction::kStopAll ? ": stopping the stack"
                                                                : "; the others keep running");
      if (plan_.on_give_up == GiveUpAction::kStopAll) stop_requested_by_failure_ = true;
    } else {
      child->finished = true;
      LogInfo() << what.str() << "; not restarted (restart: "
                << (child->spec.restart == RestartMode::kNever ? "never" : "on_failure") << ")";
    }
  }
}

void Supervisor::SettleBeforeTheLastGroup() {
  bool any = false;
  for (auto& child : children_) any = any || (child->pid > 0 && child->spec.stop_last);
  if (!any) return;
  // The others' last messages (a driver's final status) are on the bus or in the logger's socket
  // when they exit; the logger, still running, gets this long to record them before its SIGTERM
  // (a loaded machine may not schedule it at once).
  const double deadline = NowSeconds() + kLastWordsSettleS;
  while (NowSeconds() < deadline) {
    Reap(/*stopping=*/true);
    Pump(20);
  }
}

void Supervisor::StopGroup(bool stop_last_group) {
  bool any = false;
  for (auto& child : children_) {
    child->restart_at_s = -1.0;  // no restart once stopping
    if (child->pid > 0 && child->spec.stop_last == stop_last_group) {
      kill(-child->pid, SIGTERM);
      any = true;
    }
  }
  if (!any) return;
  const double deadline = NowSeconds() + plan_.stop_grace_s;
  for (;;) {
    Reap(/*stopping=*/true);
    bool running = false;
    for (auto& child : children_) {
      if (child->pid > 0 && child->spec.stop_last == stop_last_group) running = true;
    }
    if (!running) return;
    if (NowSeconds() >= deadline) break;
    Pump(20);
  }
  for (auto& child : children_) {
    if (child->pid > 0 && child->spec.stop_last == stop_last_group) {
      LogWarning() << child->spec.name << " did not stop within " << plan_.stop_grace_s
                   << " s of SIGTERM: SIGKILL";
      kill(-child->pid, SIGKILL);
      int status = 0;
      waitpid(child->pid, &status, 0);
      child->pid = -1;
      DrainAndClose(child.get());
      child->finished = true;
    }
  }
}

int Supervisor::Run() {
  const std::string bus_problem = BusNetworkProblem(settings_.lcm_url, plan_.network);
  if (!bus_problem.empty()) throw std::runtime_error(bus_problem);
  MakeDirectories(plan_.log_directory);
  for (auto& child : children_) {
    if (ShutdownRequested()) break;
    Start(child.get());
  }
  while (!ShutdownRequested() && !stop_requested_by_failure_) {
    const double now = NowSeconds();
    double next_restart = -1.0;
    bool alive = false;
    for (auto& child : children_) {
      if (child->pid > 0) alive = true;
      if (child->restart_at_s >= 0.0) {
        alive = true;
        if (now >= child->restart_at_s) {
          Start(child.get());
        } else if (next_restart < 0.0 || child->restart_at_s < next_restart) {
          next_restart = child->restart_at_s;
        }
      }
    }
    if (!alive) {
      LogInfo() << "every process has ended";
      break;
    }
    int timeout_ms = 100;  // bounds how late a dead child is noticed
    if (next_restart >= 0.0) {
      timeout_ms = std::min(timeout_ms, static_cast<int>((next_restart - now) * 1000.0) + 1);
    }
    Pump(std::max(timeout_ms, 0));
    Reap(/*stopping=*/false);
  }
  if (ShutdownRequested()) {
    LogInfo() << "stopping (signal " << ShutdownSignal() << ")";
  }
  StopGroup(/*stop_last_group=*/false);
  SettleBeforeTheLastGroup();
  StopGroup(/*stop_last_group=*/true);
  return failed_ ? 1 : 0;
}

}  // namespace slammtt
