// A program started by a test: fork/exec with its output in a file, signals, bounded waits.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace slammtt {

class ChildProcess {
 public:
  // Starts argv[0] (a path) with the given arguments; stdout goes to `output_path` (appended)
  // or, when empty, to the test's own; stderr to `error_path`, or with stdout when empty. Runs
  // in `working_directory` when given. Throws std::runtime_error if fork fails; an exec failure
  // shows as exit status 127.
  explicit ChildProcess(const std::vector<std::string>& argv, const std::string& output_path = "",
                        const std::string& error_path = "",
                        const std::string& working_directory = "");
  // Kills a child that is still running (SIGKILL) and reaps it.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  void Signal(int signal_number) const;
  // The exit code (or 128 + signal for a killed child) once it ended, waiting at most
  // `timeout_ms`; nullopt if it is still running.
  std::optional<int> Wait(int timeout_ms);
  bool running() const { return !status_.has_value(); }

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// The whole content of a file ("" if it cannot be read).
std::string ReadWholeFile(const std::string& path);
// A fresh directory under $TMPDIR (or /tmp) for one test.
std::string MakeTempDirectory(const std::string& prefix);
// Removes a directory and everything in it (tests clean up after themselves when they pass).
void RemoveDirectoryTree(const std::string& path);

}  // namespace slammtt
