// The options tables the schemas generate (common/options_schema.h, OptionsMarkdownTable), read
// back by the tests that check a module's reader and documentation: every key with its default
// as the table writes it, a configuration section that sets every key to that default, and the
// documentation page the table must appear in. Namespace slammtt::testing.
#pragma once

#include <string>
#include <vector>

namespace slammtt {
namespace testing {

struct OptionsTableRow {
  std::string key;           // as a configuration file writes it
  std::string default_text;  // the default column, as YAML reads it
};

// The rows of a generated table ("| `key` | default | ..."), in order; other lines are skipped.
std::vector<OptionsTableRow> ParseOptionsTable(const std::string& table);

// "SECTION:\n  key: default\n..." for every row.
std::string SectionOfDefaults(const std::string& section,
                              const std::vector<OptionsTableRow>& rows);

// True when no key appears twice.
bool KeysAreUnique(const std::vector<OptionsTableRow>& rows);

// The text of a file of the checkout (path relative to its root); empty when it cannot be read.
std::string ReadCheckoutFile(const std::string& relative_path);

}  // namespace testing
}  // namespace slammtt
