#include "tests/support/child_process.h"

#include <fcntl.h>
#include <ftw.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace slammtt::testing {
namespace {

// In the child only: points `target_fd` at `path` (appending); false if it cannot be opened.
bool RedirectTo(const std::string& path, int target_fd) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) return false;
  dup2(fd, target_fd);
  close(fd);
  return true;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& output_path,
                           const std::string& error_path, const std::string& working_directory) {
  if (argv.empty()) throw std::runtime_error("ChildProcess: empty argv");
  // Built before fork: the child only calls async-signal-safe functions.
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    if (!output_path.empty() && RedirectTo(output_path, 1)) dup2(1, 2);
    if (!error_path.empty()) RedirectTo(error_path, 2);
    if (!working_directory.empty() && chdir(working_directory.c_str()) != 0) _exit(126);
    execvp(args[0], args.data());
    _exit(127);
  }
}

ChildProcess::~ChildProcess() {
  if (running() && pid_ > 0) {
    kill(pid_, SIGKILL);
    Wait(5000);
  }
}

void ChildProcess::Signal(int signal_number) const {
  if (pid_ > 0 && !status_) kill(pid_, signal_number);
}

std::optional<int> ChildProcess::Wait(int timeout_ms) {
  if (status_) return status_;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return status_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& scratch_directory,
                         int timeout_ms) {
  const std::string out_path = scratch_directory + "/stdout.txt";
  const std::string err_path = scratch_directory + "/stderr.txt";
  // ChildProcess appends: start both files empty so that they hold this run only.
  std::ofstream(out_path, std::ios::trunc);
  std::ofstream(err_path, std::ios::trunc);
  ProcessResult result;
  {
    ChildProcess child(argv, out_path, err_path);
    result.exit_code = child.Wait(timeout_ms).value_or(-1);
  }  // killed and reaped here when it timed out
  result.out = ReadWholeFile(out_path);
  result.err = ReadWholeFile(err_path);
  if (result.exit_code == -1) {
    result.err += "RunProcess: " + argv[0] + " still running after " +
                  std::to_string(timeout_ms) + " ms: killed\n";
  }
  return result;
}

std::string RunCommand(const std::string& command, int* status) {
  std::FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  if (pipe == nullptr) {
    *status = -1;
    return out;
  }
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.append(buffer, n);
  *status = pclose(pipe);
  return out;
}

int Shell(const std::string& command, std::string* output) {
  int status = 0;
  const std::string out = RunCommand(command + " 2>&1", &status);
  if (output != nullptr) *output = out;
  return status;
}

std::string ReadWholeFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string MakeTempDirectory(const std::string& prefix) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base != nullptr && base[0] != '\0' ? base : "/tmp") + "/" +
                        prefix + "-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
  return buffer.data();
}

void RemoveDirectoryTree(const std::string& path) {
  if (path.empty() || path == "/") return;
  nftw(
      path.c_str(),
      [](const char* entry, const struct stat*, int, struct FTW*) { return remove(entry); }, 16,
      FTW_DEPTH | FTW_PHYS);
}

TempDir::TempDir(const std::string& prefix) : path_(MakeTempDirectory(prefix)) {}

TempDir::~TempDir() { RemoveDirectoryTree(path_); }

}  // namespace slammtt::testing
