// Programs started by tests, and the files around them: the one fork/exec helper of the test
// folders (library slammtt_test_child_process, tests/support/CMakeLists.txt).
//
// Every wait is bounded: a program that hangs fails its test with a message, it never hangs the
// test run. These helpers synchronise with other processes; they never measure time.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace slammtt::testing {

// A program running beside the test. The destructor kills it (SIGKILL) if it still runs, so a
// failed assertion never leaves a process behind.
class ChildProcess {
 public:
  // Starts argv[0] (a path, or a name looked up in PATH such as "lcm-logger") with the given
  // arguments. stdout is appended to `output_path`, or goes to the test's own stdout when empty;
  // stderr is appended to `error_path`, or follows stdout when empty. Runs in
  // `working_directory` when given. Throws std::runtime_error if fork fails; a program that
  // cannot be executed ends with status 127 (126: the working directory cannot be entered).
  explicit ChildProcess(const std::vector<std::string>& argv, const std::string& output_path = "",
                        const std::string& error_path = "",
                        const std::string& working_directory = "");
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  // Sends a signal to a child that is still running (nothing once it has been reaped).
  void Signal(int signal_number) const;
  // The exit code (128 + signal for a killed child) once it ended, waiting at most
  // `timeout_ms` (0: just look); nullopt if it is still running.
  std::optional<int> Wait(int timeout_ms);
  bool running() const { return !status_.has_value(); }

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// What a program that ran to its end printed.
struct ProcessResult {
  int exit_code = -1;  // exit status, 128 + signal, or -1 when it was killed at the timeout
  std::string out;
  std::string err;
};

// Runs `argv` (as ChildProcess) to its end with stdout and stderr captured in
// `scratch_directory`/stdout.txt and stderr.txt (overwritten by each run). A program still
// running after `timeout_ms` is killed: exit_code -1 and a line saying so at the end of err.
ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& scratch_directory,
                         int timeout_ms = 120000);

// Runs `command` with /bin/sh and returns what it printed on stdout; *status gets pclose()'s
// status (0 when the command exited with 0, -1 when it could not be started). For pipelines
// and redirections; a plain program is better started with RunProcess (no quoting).
std::string RunCommand(const std::string& command, int* status);
// The same with stderr mixed into the output; returns the status.
int Shell(const std::string& command, std::string* output = nullptr);

// The whole content of a file ("" if it cannot be read).
std::string ReadWholeFile(const std::string& path);
// A fresh directory $TMPDIR/<prefix>-XXXXXX (/tmp when TMPDIR is unset or empty). Throws
// std::runtime_error when it cannot be made.
std::string MakeTempDirectory(const std::string& prefix);
// Removes a directory and everything in it, without following symbolic links (nothing for ""
// or "/").
void RemoveDirectoryTree(const std::string& path);

// A fresh temporary directory (MakeTempDirectory) that is removed with its content when the
// object goes out of scope.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "slammtt-test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  // The path of `name` inside the directory.
  std::string File(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace slammtt::testing
