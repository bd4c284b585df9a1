// The options schema machinery (common/options_schema.h): keys from field names, unit
// conversion, ranges, the validation and the documentation visitors.
#include "common/options_schema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace slammtt {
namespace {

struct Inner {
  int count = 3;
  double rate_radps = 0.5;
};
struct Outer {
  double range_m = 30.0;
  double field_of_view_rad = M_PI;
  bool on = true;
  int mode = 1;
  Inner inner;
};

void VisitOuter(OptionVisitor* v, Outer* o) {
  v->Double("range_m", &o->range_m, OptionRange::Above(0), "a range");
  v->Double("field_of_view_rad", &o->field_of_view_rad, OptionRange::AboveUpTo(0, 360),
            "a view", OptionUnit::kDegrees);
  v->Bool("on", &o->on, "a switch");
  v->Choice("mode", &o->mode, {"first", "second"}, "a choice");
  v->BeginGroup("inner");
  v->Int("count", &o->inner.count, OptionRange::Between(1, 10), "a count");
  v->Double("rate_radps", &o->inner.rate_radps, OptionRange::AtLeast(0), "a rate",
            OptionUnit::kDegrees);
  v->EndGroup();
}

TEST(OptionsSchemaTest, KeysAreFieldNamesWithTheirGroupAndUnit) {
  OptionsMarkdownTable table;
  Outer defaults;
  VisitOuter(&table, &defaults);
  EXPECT_EQ(table.Table(),
            "| key | default | valid | what |\n"
            "|---|---|---|---|\n"
            "| `range_m` | 30 | > 0 | a range |\n"
            "| `field_of_view_deg` | 180 | (0, 360] | a view |\n"
            "| `on` | true | true, false | a switch |\n"
            "| `mode` | second | first, second | a choice |\n"
            "| `inner_count` | 3 | [1, 10] | a count |\n"
            "| `inner_rate_degps` | 28.6479 | >= 0 | a rate |\n");
}

TEST(OptionsSchemaTest, RangesAndConversions) {
  EXPECT_TRUE(OptionRange::Above(0).Contains(1e-300));
  EXPECT_FALSE(OptionRange::Above(0).Contains(0.0));
  EXPECT_TRUE(OptionRange::AtLeast(0).Contains(0.0));
  EXPECT_FALSE(OptionRange::Open(0, 1).Contains(1.0));
  EXPECT_TRUE(OptionRange::AboveUpTo(0, 360).Contains(360.0));
  EXPECT_FALSE(OptionRange::Any().Contains(std::nan("")));
  EXPECT_FALSE(OptionRange::Any().Contains(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(OptionRange::Between(1, 4096).Requirement(), "in [1, 4096]");
  EXPECT_EQ(OptionRange::AtLeast(0).Requirement(), ">= 0");
  // The conversion every reader uses: x * pi / 180 (not x * (pi / 180)), exactly.
  EXPECT_EQ(FromConfigUnit(2.0, OptionUnit::kDegrees), 2.0 * M_PI / 180.0);
  EXPECT_EQ(ToConfigUnit(M_PI, OptionUnit::kDegrees), 180.0);
  EXPECT_EQ(FromConfigUnit(2.0, OptionUnit::kAsIs), 2.0);
}

TEST(OptionsSchemaTest, TheRangeCheckNamesTheFirstBadKeyInItsUnit) {
  Outer o;
  OptionRangeCheck ok;
  VisitOuter(&ok, &o);
  EXPECT_EQ(ok.problem(), "");
  o.field_of_view_rad = 7.0;  // 401 degrees
  o.inner.count = 0;
  OptionRangeCheck bad;
  VisitOuter(&bad, &o);
  EXPECT_EQ(bad.problem(), "field_of_view_deg = 401.07: must be in (0, 360]");
  o.field_of_view_rad = M_PI;
  OptionRangeCheck count;
  VisitOuter(&count, &o);
  EXPECT_EQ(count.problem(), "inner_count = 0: must be in [1, 10]");
  o.inner.count = 3;
  o.mode = 2;
  OptionRangeCheck choice;
  VisitOuter(&choice, &o);
  EXPECT_EQ(choice.problem(), "mode is not one of its choices");
}

// The first problem in two parts, for a caller that names the key its own way.
TEST(OptionsSchemaTest, TheRangeCheckGivesTheKeyAndTheDetailApart) {
  Outer o;
  o.inner.rate_radps = -1.0;
  o.range_m = 0.0;
  OptionRangeCheck check;
  VisitOuter(&check, &o);
  EXPECT_EQ(check.problem(), "range_m = 0: must be > 0");
  EXPECT_EQ(check.problem_key(), "range_m");
  EXPECT_EQ(check.problem_detail(), "must be > 0, got 0");
}

struct Named {
  std::string port = "/dev/ttyUSB0";
  std::string key_file;
};

TEST(OptionsSchemaTest, TextOptionsAreDocumentedAndNeverOutOfRange) {
  Named n;
  const auto visit = [](OptionVisitor* v, Named* named) {
    v->String("port", &named->port, "the device");
    v->String("key_file", &named->key_file, "a file");
  };
  OptionsMarkdownTable table;
  visit(&table, &n);
  EXPECT_EQ(table.Table(),
            "| key | default | valid | what |\n"
            "|---|---|---|---|\n"
            "| `port` | /dev/ttyUSB0 | text | the device |\n"
            "| `key_file` | \"\" | text | a file |\n");
  OptionRangeCheck check;
  visit(&check, &n);
  EXPECT_EQ(check.problem(), "");
}

}  // namespace
}  // namespace slammtt
