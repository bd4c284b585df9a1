#include "runtime/config.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace slammtt {

struct Config::Impl {
  YAML::Node node;
};

struct Config::Shared {
  std::string source;
  std::set<std::string> used_paths;
};

namespace {

// The largest configuration or scenario file read: the shipped ones are a few kilobytes.
constexpr off_t kMaxConfigFileBytes = 16 << 20;

std::string Describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "\"" + node.Scalar() + "\"";
}

int LineOfNode(const YAML::Node& node);

// The text of a mapping key; a key that is a list or a mapping ("[]: 3") is bad input, reported
// like any other, never a yaml-cpp exception that names no file.
std::string KeyText(const YAML::Node& key, const std::string& source, const std::string& path) {
  if (!key.IsScalar()) {
    const int line = LineOfNode(key);
    throw ConfigError(source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                      (path.empty() ? "" : path + ": ") + "keys must be plain text, got " +
                      Describe(key));
  }
  return key.Scalar();
}

int LineOfNode(const YAML::Node& node) {
  if (!node.IsDefined()) return -1;
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? -1 : mark.line + 1;
}

// The keys of a mapping in file order. yaml-cpp keeps a key given twice and every lookup finds
// the first, so the second value would be ignored without a word: that is an error, like an
// unknown key.
std::vector<std::string> MappingKeys(const YAML::Node& map, const std::string& source,
                                     const std::string& path) {
  std::vector<std::string> keys;
  std::map<std::string, int> first_line;
  for (const auto& entry : map) {
    const std::string key = KeyText(entry.first, source, path);
    const int line = LineOfNode(entry.first);
    const auto [it, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      throw ConfigError(source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                        (path.empty() ? key : path + "." + key) + ": duplicate key (first at line " +
                        std::to_string(it->second) + ")");
    }
    keys.push_back(key);
  }
  return keys;
}

}  // namespace

Config::Config()
    : impl_(std::make_shared<Impl>(Impl{YAML::Node(YAML::NodeType::Map)})),
      shared_(std::make_shared<Shared>()) {
  shared_->source = "<defaults>";
}

Config::Config(std::shared_ptr<const Impl> impl, std::shared_ptr<Shared> shared, std::string path)
    : impl_(std::move(impl)), shared_(std::move(shared)), path_(std::move(path)) {}

Config Config::FromString(const std::string& yaml_text, const std::string& source) {
  auto shared = std::make_shared<Shared>();
  shared->source = source;
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    std::ostringstream out;
    out << source << ":" << (e.mark.is_null() ? 0 : e.mark.line + 1) << ": not valid YAML: "
        << e.msg;
    throw ConfigError(out.str());
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file is an empty map
  if (!root.IsMap()) {
    throw ConfigError(source + ":" + std::to_string(std::max(1, LineOfNode(root))) +
                      ": the top level must be a mapping of keys, got " + Describe(root));
  }
  return Config(std::make_shared<Impl>(Impl{root}), shared, "");
}

Config Config::LoadFile(const std::string& path) {
  // A configuration is a regular file of human size: a directory would read as an empty file
  // (an empty configuration, silently), /dev/zero or a FIFO would never end. O_NONBLOCK keeps
  // open() of a FIFO from waiting for a writer.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) throw ConfigError(path + ": cannot open file: " + std::strerror(errno));
  struct stat info {};
  const bool regular = fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  const off_t size = info.st_size;
  std::string text;
  if (regular && size <= kMaxConfigFileBytes) {
    text.resize(static_cast<size_t>(size));
    size_t used = 0;
    while (used < text.size()) {
      const ssize_t n = read(fd, text.data() + used, text.size() - used);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      used += static_cast<size_t>(n);
    }
    text.resize(used);
  }
  close(fd);
  if (!regular) throw ConfigError(path + ": not a regular file (a configuration is a YAML file)");
  if (size > kMaxConfigFileBytes) {
    throw ConfigError(path + ": " + std::to_string(size) +
                      " bytes is not a configuration (at most " +
                      std::to_string(kMaxConfigFileBytes) + ")");
  }
  return FromString(text, path);
}

const std::string& Config::Source() const { return shared_->source; }

std::string Config::ChildPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool Config::Has(const std::string& key) const {
  return impl_->node.IsMap() && impl_->node[key].IsDefined() && !impl_->node[key].IsNull();
}
bool Config::IsMap() const { return impl_->node.IsMap(); }
bool Config::IsSequence() const { return impl_->node.IsSequence(); }
bool Config::IsScalar() const { return impl_->node.IsScalar(); }

std::vector<std::string> Config::Keys() const {
  if (!impl_->node.IsMap()) return {};
  return MappingKeys(impl_->node, shared_->source, path_);
}

size_t Config::Size() const { return impl_->node.IsSequence() ? impl_->node.size() : 0; }

std::string Config::Where() const {
  const int line = LineOfNode(impl_->node);
  return shared_->source + (line > 0 ? ":" + std::to_string(line) : std::string());
}

std::string Config::LineOf(const std::string& key) const {
  if (impl_->node.IsMap()) {
    for (const auto& entry : impl_->node) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) {
        const int line = LineOfNode(entry.first);
        if (line > 0) return shared_->source + ":" + std::to_string(line);
      }
    }
  }
  return Where();
}

void Config::Fail(const std::string& message) const {
  throw ConfigError(Where() + ": " + (path_.empty() ? "" : path_ + ": ") + message);
}

void Config::FailKey(const std::string& key, const std::string& message) const {
  throw ConfigError(LineOf(key) + ": " + ChildPath(key) + ": " + message);
}

Config Config::Lookup(const std::string& key) const {
  if (!impl_->node.IsMap()) Fail("expected a mapping of keys, got " + Describe(impl_->node));
  const std::string child_path = ChildPath(key);
  shared_->used_paths.insert(child_path);
  YAML::Node child = impl_->node[key];
  return Config(std::make_shared<Impl>(Impl{child}), shared_, child_path);
}

double Config::AsDouble() const {
  const YAML::Node& n = impl_->node;
  if (!n.IsScalar()) Fail("expected a number, got " + Describe(n));
  double value = 0.0;
  try {
    value = n.as<double>();
  } catch (const YAML::Exception&) {
    Fail("expected a number, got " + Describe(n));
  }
  if (!std::isfinite(value)) Fail("expected a finite number, got " + Describe(n));
  return value;
}

int64_t Config::AsInt() const {
  const YAML::Node& n = impl_->node;
  if (!n.IsScalar()) Fail("expected a whole number, got " + Describe(n));
  try {
    return n.as<int64_t>();
  } catch (const YAML::Exception&) {
    Fail("expected a whole number, got " + Describe(n));
  }
}

std::string Config::AsString() const {
  const YAML::Node& n = impl_->node;
  if (!n.IsScalar()) Fail("expected a text value, got " + Describe(n));
  return n.Scalar();
}

std::vector<double> Config::AsDoubles() const {
  if (!impl_->node.IsSequence()) Fail("expected a list of numbers, got " + Describe(impl_->node));
  std::vector<double> values;
  for (const Config& element : Elements()) values.push_back(element.AsDouble());
  return values;
}

namespace {
bool Present(const YAML::Node& n) { return n.IsDefined() && !n.IsNull(); }
}  // namespace

double Config::GetDouble(const std::string& key, double fallback) const {
  const Config c = Lookup(key);
  return Present(c.impl_->node) ? c.AsDouble() : fallback;
}

int64_t Config::GetInt(const std::string& key, int64_t fallback) const {
  const Config c = Lookup(key);
  return Present(c.impl_->node) ? c.AsInt() : fallback;
}

bool Config::GetBool(const std::string& key, bool fallback) const {
  const Config c = Lookup(key);
  if (!Present(c.impl_->node)) return fallback;
  if (!c.impl_->node.IsScalar()) c.Fail("expected true or false, got " + Describe(c.impl_->node));
  try {
    return c.impl_->node.as<bool>();
  } catch (const YAML::Exception&) {
    c.Fail("expected true or false, got " + Describe(c.impl_->node));
  }
}

std::string Config::GetString(const std::string& key, const std::string& fallback) const {
  const Config c = Lookup(key);
  return Present(c.impl_->node) ? c.AsString() : fallback;
}

std::vector<double> Config::GetDoubles(const std::string& key,
                                       const std::vector<double>& fallback) const {
  const Config c = Lookup(key);
  return Present(c.impl_->node) ? c.AsDoubles() : fallback;
}

double Config::RequireDouble(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing key");
  return GetDouble(key, 0.0);
}
int64_t Config::RequireInt(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing key");
  return GetInt(key, 0);
}
bool Config::RequireBool(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing key");
  return GetBool(key, false);
}
std::string Config::RequireString(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing key");
  return GetString(key, "");
}
std::vector<double> Config::RequireDoubles(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing key");
  return GetDoubles(key, {});
}

Config Config::Child(const std::string& key) const {
  Config c = Lookup(key);
  if (!Present(c.impl_->node)) {
    return Config(std::make_shared<Impl>(Impl{YAML::Node(YAML::NodeType::Map)}), shared_, c.path_);
  }
  if (!c.impl_->node.IsMap()) c.Fail("expected a mapping of keys, got " + Describe(c.impl_->node));
  return c;
}

Config Config::RequireChild(const std::string& key) const {
  if (!Has(key)) FailKey(key, "missing section");
  return Child(key);
}

std::vector<Config> Config::Elements() const {
  if (!impl_->node.IsSequence()) Fail("expected a list, got " + Describe(impl_->node));
  std::vector<Config> elements;
  for (size_t i = 0; i < impl_->node.size(); ++i) {
    const std::string element_path = path_ + "[" + std::to_string(i) + "]";
    shared_->used_paths.insert(element_path);
    elements.push_back(
        Config(std::make_shared<Impl>(Impl{impl_->node[i]}), shared_, element_path));
  }
  return elements;
}

std::vector<Config> Config::Items(const std::string& key) const {
  const Config c = Lookup(key);
  if (!Present(c.impl_->node)) return {};
  return c.Elements();
}

void Config::CheckKeysAmong(const std::vector<std::string>& allowed) const {
  for (const std::string& key : Keys()) {
    bool known = false;
    for (const std::string& a : allowed) known = known || (a == key);
    if (!known) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      FailKey(key, "unknown key (known here: " + list + ")");
    }
  }
}

void Config::CheckUnused() const {
  const YAML::Node& n = impl_->node;
  if (n.IsMap()) {
    MappingKeys(n, shared_->source, path_);  // a key given twice is an error
    for (const auto& entry : n) {
      const std::string key = KeyText(entry.first, shared_->source, path_);
      const std::string child_path = ChildPath(key);
      if (shared_->used_paths.count(child_path) == 0) FailKey(key, "unknown key");
      Config(std::make_shared<Impl>(Impl{entry.second}), shared_, child_path).CheckUnused();
    }
  } else if (n.IsSequence()) {
    for (size_t i = 0; i < n.size(); ++i) {
      const std::string element_path = path_ + "[" + std::to_string(i) + "]";
      if (shared_->used_paths.count(element_path) == 0) continue;  // list of plain values
      Config(std::make_shared<Impl>(Impl{n[i]}), shared_, element_path).CheckUnused();
    }
  }
}

}  // namespace slammtt
