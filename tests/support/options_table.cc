#include "tests/support/options_table.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace slammtt {
namespace testing {

std::vector<OptionsTableRow> ParseOptionsTable(const std::string& table) {
  std::vector<OptionsTableRow> rows;
  std::istringstream lines(table);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const size_t key_end = line.find('`', 3);
    if (key_end == std::string::npos) continue;
    const size_t value_end = line.find(" |", key_end + 4);
    rows.push_back({line.substr(3, key_end - 3),
                    line.substr(key_end + 4, value_end - key_end - 4)});
  }
  return rows;
}

std::string SectionOfDefaults(const std::string& section,
                              const std::vector<OptionsTableRow>& rows) {
  std::string yaml = section + ":\n";
  for (const OptionsTableRow& row : rows) yaml += "  " + row.key + ": " + row.default_text + "\n";
  return yaml;
}

bool KeysAreUnique(const std::vector<OptionsTableRow>& rows) {
  std::vector<std::string> keys;
  for (const OptionsTableRow& row : rows) keys.push_back(row.key);
  std::sort(keys.begin(), keys.end());
  return std::adjacent_find(keys.begin(), keys.end()) == keys.end();
}

std::string ReadCheckoutFile(const std::string& relative_path) {
  std::ifstream file(std::string(SLAMMTT_SOURCE_DIR) + "/" + relative_path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace testing
}  // namespace slammtt
