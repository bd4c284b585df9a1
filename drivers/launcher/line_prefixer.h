// Cuts a child's output into lines and puts its name in front of each, so that the output of
// every process of the stack can share one terminal or one journal and still be told apart:
//   p3dx      | slammtt-p3dx: info: connected to 'Robbie' (Pioneer p3dx) on serial:/dev/ttyUSB0@9600
// Pure: bytes in, text out.
#pragma once

#include <cstddef>
#include <string>

namespace slammtt {

class LinePrefixer {
 public:
  // `prefix` goes in front of every line as it is ("p3dx      | "). A line longer than
  // `max_line_bytes` is cut there and continues on the next prefixed line, so one process
  // cannot hold the others' output back forever.
  explicit LinePrefixer(std::string prefix, size_t max_line_bytes = 8192);

  // The complete lines in `data` (with what was kept from earlier calls), each prefixed and
  // ending in '\n'. A partial last line is kept for later.
  std::string Feed(const char* data, size_t size);
  // What is left: a last line without its newline, prefixed and terminated (end of output).
  std::string Flush();

 private:
  std::string prefix_;
  size_t max_line_bytes_;
  std::string partial_;
};

// "name" padded with spaces to `width`, then " | ".
std::string OutputPrefix(const std::string& name, size_t width);

}  // namespace slammtt
