#include "drivers/launcher/line_prefixer.h"

#include <utility>

namespace slammtt {

LinePrefixer::LinePrefixer(std::string prefix, size_t max_line_bytes)
    : prefix_(std::move(prefix)), max_line_bytes_(max_line_bytes == 0 ? 1 : max_line_bytes) {}

std::string LinePrefixer::Feed(const char* data, size_t size) {
  std::string out;
  for (size_t i = 0; i < size; ++i) {
    const char c = data[i];
    if (c == '\n') {
      out += prefix_;
      out += partial_;
      out += '\n';
      partial_.clear();
      continue;
    }
    partial_.push_back(c);
    if (partial_.size() >= max_line_bytes_) {
      out += prefix_;
      out += partial_;
      out += '\n';
      partial_.clear();
    }
  }
  return out;
}

std::string LinePrefixer::Flush() {
  if (partial_.empty()) return {};
  std::string out = prefix_ + partial_ + '\n';
  partial_.clear();
  return out;
}

std::string OutputPrefix(const std::string& name, size_t width) {
  std::string prefix = name;
  if (prefix.size() < width) prefix.append(width - prefix.size(), ' ');
  return prefix + " | ";
}

}  // namespace slammtt
