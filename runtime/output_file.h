// A file that appears under its name only when it is complete, and that is never written
// through a link someone planted: every output of the tools (logs of slammtt-replay and
// slammtt-world through LogWriter, reports of slammtt-eval) is one.
//
// The file is created in the directory of its final path as an unnamed file (Linux O_TMPFILE,
// open(2)): there is no name to follow, and if the process dies, even by SIGKILL, nothing is
// left behind. Where the file system has no O_TMPFILE (or /proc is missing, which the naming
// step needs), it is a new "<path>.partial.<pid>.<n>" created with O_CREAT | O_EXCL, which
// refuses any existing file or link of that name; killing the process then leaves that file.
// Commit() flushes it to disk, gives it a fresh name beside the target (linkat through
// /proc/self/fd, exclusive as well) and renames that onto the final path, which replaces a
// file or a link of that name rather than writing through it. The destructor of an uncommitted
// file discards it.
#pragma once

#include <cstdio>
#include <string>

namespace slammtt {

class OutputFile {
 public:
  // Throws std::runtime_error, one line naming `path`, when the file cannot be created.
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Where to write (buffered); valid until Commit() or destruction.
  std::FILE* stream() { return stream_; }
  // Flushes, syncs and moves the file into place. Throws std::runtime_error naming the path on
  // a write error (the file is then discarded).
  void Commit();

  const std::string& path() const { return path_; }
  // The name the unfinished file has on disk: "" for an unnamed (O_TMPFILE) one.
  const std::string& partial_path() const { return partial_path_; }

 private:
  void Discard();

  std::string path_;
  std::string partial_path_;
  std::FILE* stream_ = nullptr;
  bool committed_ = false;
};

}  // namespace slammtt
