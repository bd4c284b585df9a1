// The stage adapter on encoded messages, through a capturing MessageSink (what replay does), and
// the `segmenter:` configuration section.
#include "perception/segmenter_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "tests/perception/scan_message.h"
#include "tests/perception/synthetic_scan.h"
#include "tests/support/options_table.h"

namespace slammtt {
namespace {

using testing_support::CastScan;
using testing_support::Circle;
using testing_support::EvenAngles;

struct Published {
  std::string channel;
  std::vector<uint8_t> bytes;
};

class CapturingSink : public MessageSink {
 public:
  void Publish(const std::string& channel, const void* data, int size) override {
    const auto* p = static_cast<const uint8_t*>(data);
    messages.push_back(Published{channel, std::vector<uint8_t>(p, p + size)});
  }
  std::vector<Published> messages;
};

const std::vector<Circle> kScene = {{2.0, 0.5, 0.2}, {-1.5, 2.5, 0.25}, {0.5, -3.0, 0.15}};

slammtt_msgs::laser_scan_t MakeScanMessage(int64_t utime, int64_t sequence,
                                           const std::vector<Circle>& scene = kScene) {
  return testing_support::ScanMessage(CastScan(scene, EvenAngles(0.0, 2.0 * M_PI, 400, true)),
                                      utime, sequence);
}

SegmenterStage MakeStage() {
  return SegmenterStage(SegmenterOptions{}, "LASER_SCAN", "FEATURES", "STAGE_TIMING");
}

TEST(SegmenterStageTest, PublishesFeaturesWithTheScanTimeAndTiming) {
  SegmenterStage stage = MakeStage();
  EXPECT_EQ(stage.Name(), "segmenter");
  ASSERT_EQ(stage.InputChannels(), std::vector<std::string>{"LASER_SCAN"});
  const slammtt_msgs::laser_scan_t scan = MakeScanMessage(1700000000123456, 42);
  const std::vector<uint8_t> bytes = Encode(scan);
  CapturingSink sink;
  stage.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), sink);
  ASSERT_EQ(sink.messages.size(), 2u);
  ASSERT_EQ(sink.messages[0].channel, "FEATURES");
  ASSERT_EQ(sink.messages[1].channel, "STAGE_TIMING");

  slammtt_msgs::features_t features;
  ASSERT_TRUE(Decode(sink.messages[0].bytes.data(),
                     static_cast<int>(sink.messages[0].bytes.size()), &features));
  EXPECT_EQ(features.utime, 1700000000123456);
  EXPECT_EQ(features.sequence, 42);
  ASSERT_EQ(features.num_features, 3);
  // Same numbers as the library gives for the same scan.
  ScanView view = MakeScanView(scan.angle_rad, scan.range_m, scan.valid);
  view.range_min_m = scan.range_min_m;
  view.range_max_m = scan.range_max_m;
  const std::vector<Feature> expected = SegmentScan(view, SegmenterOptions{});
  ASSERT_EQ(expected.size(), 3u);
  for (size_t i = 0; i < expected.size(); ++i) {
    const slammtt_msgs::feature_t& f = features.features[i];
    EXPECT_EQ(f.range_m, expected[i].range_m);
    EXPECT_EQ(f.bearing_rad, expected[i].bearing_rad);
    EXPECT_EQ(f.width_m, expected[i].width_m);
    EXPECT_EQ(f.num_points, expected[i].num_points);
    EXPECT_EQ(f.range_var_m2, expected[i].covariance(0, 0));
    EXPECT_EQ(f.bearing_var_rad2, expected[i].covariance(1, 1));
    EXPECT_EQ(f.range_bearing_cov_m_rad, 0.0);
    EXPECT_GT(f.range_var_m2, 0.0);
    EXPECT_GT(f.bearing_var_rad2, 0.0);
  }

  slammtt_msgs::stage_timing_t timing;
  ASSERT_TRUE(Decode(sink.messages[1].bytes.data(),
                     static_cast<int>(sink.messages[1].bytes.size()), &timing));
  EXPECT_EQ(timing.utime, 1700000000123456);
  EXPECT_EQ(timing.stage, "segmenter");
  EXPECT_EQ(timing.substage,
            (std::vector<std::string>{"decode", "sort", "cluster", "lines", "features", "people",
                                      "publish"}));
  ASSERT_EQ(timing.num_counters, static_cast<int32_t>(timing.counter_name.size()));
  auto counter = [&](const std::string& name) -> int64_t {
    for (size_t i = 0; i < timing.counter_name.size(); ++i) {
      if (timing.counter_name[i] == name) return timing.counter_value[i];
    }
    ADD_FAILURE() << "no counter " << name;
    return -1;
  };
  EXPECT_EQ(counter("beams"), 400);
  EXPECT_EQ(counter("features"), 3);
  EXPECT_EQ(counter("clusters"), 3);
  EXPECT_EQ(counter("beams_used") + counter("beams_dropped"), 400);
  EXPECT_EQ(counter("sorted"), 0);
  EXPECT_GE(timing.total_ns, 0);
  EXPECT_EQ(stage.counters().scans_handled, 1);
  EXPECT_EQ(stage.counters().features_published, 3);
}

TEST(SegmenterStageTest, FeaturesOutputIsByteIdenticalRunToRun) {
  const std::vector<uint8_t> bytes = Encode(MakeScanMessage(1000, 1));
  CapturingSink a;
  CapturingSink b;
  SegmenterStage first = MakeStage();
  SegmenterStage second = MakeStage();
  first.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), a);
  second.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), b);
  first.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), a);
  ASSERT_EQ(a.messages.size(), 4u);
  EXPECT_EQ(a.messages[0].bytes, b.messages[0].bytes);
  EXPECT_EQ(a.messages[0].bytes, a.messages[2].bytes);
}

TEST(SegmenterStageTest, EmptyScanPublishesAnEmptyFeatureList) {
  SegmenterStage stage = MakeStage();
  slammtt_msgs::laser_scan_t scan = MakeScanMessage(5, 6, {});  // nothing in range
  CapturingSink sink;
  std::vector<uint8_t> bytes = Encode(scan);
  stage.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), sink);
  scan.num_beams = 0;  // and a scan without beams at all
  scan.angle_rad.clear();
  scan.range_m.clear();
  scan.intensity.clear();
  scan.valid.clear();
  bytes = Encode(scan);
  stage.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), sink);
  ASSERT_EQ(sink.messages.size(), 4u);
  for (size_t i : {0u, 2u}) {
    slammtt_msgs::features_t features;
    ASSERT_TRUE(Decode(sink.messages[i].bytes.data(),
                       static_cast<int>(sink.messages[i].bytes.size()), &features));
    EXPECT_EQ(features.utime, 5);
    EXPECT_EQ(features.sequence, 6);
    EXPECT_EQ(features.num_features, 0);
  }
  EXPECT_EQ(stage.counters().scans_handled, 2);
  EXPECT_EQ(stage.counters().scans_rejected, 0);
}

TEST(SegmenterStageTest, MalformedMessagesAreCountedNotThrownNorPublished) {
  SegmenterStage stage = MakeStage();
  CapturingSink sink;
  const std::vector<uint8_t> good = Encode(MakeScanMessage(7, 8));
  // Garbage, empty, a null pointer.
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  stage.Handle("LASER_SCAN", garbage, 5, sink);
  stage.Handle("LASER_SCAN", good.data(), 0, sink);
  stage.Handle("LASER_SCAN", nullptr, 100, sink);
  // Truncated.
  stage.Handle("LASER_SCAN", good.data(), static_cast<int>(good.size()) - 1, sink);
  // A num_beams that claims 2^31 - 1 beams (the decoder would try to allocate 13 GB).
  std::vector<uint8_t> huge = good;
  huge[40] = 0x7f;
  huge[41] = huge[42] = huge[43] = 0xff;
  stage.Handle("LASER_SCAN", huge.data(), static_cast<int>(huge.size()), sink);
  // Negative num_beams.
  std::vector<uint8_t> negative = good;
  negative[40] = 0xff;
  stage.Handle("LASER_SCAN", negative.data(), static_cast<int>(negative.size()), sink);
  // Right size, wrong type hash.
  std::vector<uint8_t> wrong_hash = good;
  wrong_hash[0] ^= 0x55;
  stage.Handle("LASER_SCAN", wrong_hash.data(), static_cast<int>(wrong_hash.size()), sink);
  // Another message type on the scan channel.
  slammtt_msgs::odometry_t odometry{};
  const std::vector<uint8_t> other = Encode(odometry);
  stage.Handle("LASER_SCAN", other.data(), static_cast<int>(other.size()), sink);
  EXPECT_TRUE(sink.messages.empty());
  EXPECT_EQ(stage.counters().scans_rejected, 8);
  EXPECT_EQ(stage.counters().scans_handled, 0);
  // A message on a channel the stage does not consume is ignored, not rejected.
  stage.Handle("ODOMETRY", other.data(), static_cast<int>(other.size()), sink);
  EXPECT_EQ(stage.counters().scans_rejected, 8);
  // The stage still works.
  stage.Handle("LASER_SCAN", good.data(), static_cast<int>(good.size()), sink);
  EXPECT_EQ(sink.messages.size(), 2u);
  EXPECT_EQ(stage.counters().scans_handled, 1);
}

// A flood of bad messages is counted in full but reported only the 1st, 10th, 100th, ... time
// (runtime/log.h IsReportable), one line each.
TEST(SegmenterStageTest, RejectionsAreReportedAtPowersOfTen) {
  SegmenterStage stage = MakeStage();
  CapturingSink sink;
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  ::testing::internal::CaptureStderr();
  for (int i = 0; i < 120; ++i) stage.Handle("LASER_SCAN", garbage, 5, sink);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(stage.counters().scans_rejected, 120);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 3) << err;
  EXPECT_NE(err.find("(1 rejected so far)\n"), std::string::npos) << err;
  EXPECT_NE(err.find("(10 rejected so far)\n"), std::string::npos) << err;
  EXPECT_NE(err.find("(100 rejected so far)\n"), std::string::npos) << err;
  EXPECT_TRUE(sink.messages.empty());
}

TEST(SegmenterStageTest, ReadsOptionsFromTheSegmenterSection) {
  const Config config = Config::FromString(
      "segmenter:\n"
      "  lambda_deg: 15\n"
      "  sigma_r_m: 0.05\n"
      "  max_beam_gap_deg: 3\n"
      "  max_dropped_beams: 2\n"
      "  duplicate_angle_tolerance_deg: 0.01\n"
      "  min_range_m: 0.2\n"
      "  max_range_m: 8\n"
      "  min_points: 4\n"
      "  max_width_m: 1.0\n"
      "  centre_rule: middle_point\n"
      "  max_object_radius_m: 0.5\n"
      "  bearing_sigma_deg: 2\n"
      "  shape_sigma_fraction: 0.1\n",
      "stack.yaml");
  const SegmenterOptions o = ReadSegmenterOptions(config.Child("segmenter"));
  EXPECT_DOUBLE_EQ(o.lambda_rad, 15.0 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(o.sigma_r_m, 0.05);
  EXPECT_DOUBLE_EQ(o.max_beam_gap_rad, 3.0 * M_PI / 180.0);
  EXPECT_EQ(o.max_dropped_beams, 2);
  EXPECT_DOUBLE_EQ(o.duplicate_angle_tolerance_rad, 0.01 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(o.min_range_m, 0.2);
  EXPECT_DOUBLE_EQ(o.max_range_m, 8.0);
  EXPECT_EQ(o.min_points, 4);
  EXPECT_DOUBLE_EQ(o.max_width_m, 1.0);
  EXPECT_EQ(o.centre_rule, CentreRule::kMiddlePoint);
  EXPECT_DOUBLE_EQ(o.max_object_radius_m, 0.5);
  EXPECT_DOUBLE_EQ(o.bearing_sigma_rad, 2.0 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(o.shape_sigma_fraction, 0.1);
  // An absent section gives the defaults (the paper's lambda and sigma).
  const SegmenterOptions defaults = ReadSegmenterOptions(Config());
  EXPECT_DOUBLE_EQ(defaults.lambda_rad, 20.0 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(defaults.sigma_r_m, 0.03);
  EXPECT_EQ(defaults.centre_rule, CentreRule::kCircleFit);
  EXPECT_TRUE(std::isinf(defaults.max_range_m));
}

void ExpectConfigError(const std::string& yaml, const std::string& expected_text) {
  const Config config = Config::FromString(yaml, "stack.yaml");
  try {
    ReadSegmenterOptions(config.Child("segmenter"));
    ADD_FAILURE() << "no error for:\n" << yaml;
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(expected_text), std::string::npos) << what;
    EXPECT_NE(what.find("stack.yaml"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(SegmenterStageTest, BadConfigurationNamesTheKey) {
  ExpectConfigError("segmenter:\n  lamda_deg: 20\n", "lamda_deg");
  ExpectConfigError("segmenter:\n  lambda_deg: twenty\n", "lambda_deg");
  ExpectConfigError("segmenter:\n  lambda_deg: 95\n", "lambda_deg");
  ExpectConfigError("segmenter:\n  sigma_r_m: -0.03\n", "sigma_r_m");
  ExpectConfigError("segmenter:\n  min_points: 0\n", "min_points");
  ExpectConfigError("segmenter:\n  max_dropped_beams: -1\n", "max_dropped_beams");
  ExpectConfigError("segmenter:\n  min_points: 2.5\n", "min_points");
  ExpectConfigError("segmenter:\n  centre_rule: centroid\n", "centre_rule");
  ExpectConfigError("segmenter:\n  min_range_m: 5\n  max_range_m: 4\n", "max_range_m");
  ExpectConfigError("segmenter:\n  bearing_sigma_deg: 0\n", "bearing_sigma_deg");
}

TEST(SegmenterStageTest, ReadsTheClassificationOptions) {
  const Config config = Config::FromString(
      "segmenter:\n"
      "  extract_lines: false\n"
      "  line_split_distance_m: 0.04\n"
      "  line_split_range_fraction: 0.01\n"
      "  min_line_points: 7\n"
      "  min_line_length_m: 0.6\n"
      "  straight_piece_width_m: 0.25\n"
      "  leg_min_diameter_m: 0.07\n"
      "  leg_max_diameter_m: 0.2\n"
      "  leg_diameter_margin_m: 0.02\n"
      "  leg_convexity_floor: 0.3\n"
      "  detect_people: false\n"
      "  leg_threshold: 0.7\n"
      "  leg_nominal_diameter_m: 0.1\n"
      "  person_min_leg_separation_m: 0.05\n"
      "  person_max_leg_separation_m: 0.7\n"
      "  person_single_leg_threshold: 0.8\n"
      "  person_pair_centre_sigma_m: 0.04\n"
      "  person_single_leg_offset_sigma_m: 0.2\n"
      "  depth_edge_m: 0.5\n",
      "stack.yaml");
  const SegmenterOptions o = ReadSegmenterOptions(config.Child("segmenter"));
  EXPECT_FALSE(o.extract_lines);
  EXPECT_DOUBLE_EQ(o.line_split_distance_m, 0.04);
  EXPECT_DOUBLE_EQ(o.line_split_range_fraction, 0.01);
  EXPECT_EQ(o.min_line_points, 7);
  EXPECT_DOUBLE_EQ(o.min_line_length_m, 0.6);
  EXPECT_DOUBLE_EQ(o.straight_piece_width_m, 0.25);
  EXPECT_DOUBLE_EQ(o.leg.min_diameter_m, 0.07);
  EXPECT_DOUBLE_EQ(o.leg.max_diameter_m, 0.2);
  EXPECT_DOUBLE_EQ(o.leg.diameter_margin_m, 0.02);
  EXPECT_DOUBLE_EQ(o.leg.convexity_floor, 0.3);
  EXPECT_FALSE(o.detect_people);
  EXPECT_DOUBLE_EQ(o.leg_threshold, 0.7);
  EXPECT_DOUBLE_EQ(o.leg_nominal_diameter_m, 0.1);
  EXPECT_DOUBLE_EQ(o.person.min_leg_separation_m, 0.05);
  EXPECT_DOUBLE_EQ(o.person.max_leg_separation_m, 0.7);
  EXPECT_DOUBLE_EQ(o.person.single_leg_threshold, 0.8);
  EXPECT_DOUBLE_EQ(o.person.pair_centre_sigma_m, 0.04);
  EXPECT_DOUBLE_EQ(o.person.single_leg_offset_sigma_m, 0.2);
  EXPECT_DOUBLE_EQ(o.depth_edge_m, 0.5);
  ExpectConfigError("segmenter:\n  leg_threshold: 1.5\n", "leg_threshold");
  ExpectConfigError("segmenter:\n  min_line_points: 2\n", "min_line_points");
  ExpectConfigError("segmenter:\n  extract_lines: maybe\n", "extract_lines");
  ExpectConfigError("segmenter:\n  person_max_leg_separation_m: 0.05\n",
                    "person_max_leg_separation_m must be > person_min_leg_separation_m");
  ExpectConfigError("segmenter:\n  leg_max_diameter_m: 0.05\n",
                    "leg_max_diameter_m must be >= leg_min_diameter_m");
  ExpectConfigError("segmenter:\n  leg_convexity_floor: -0.1\n",
                    "segmenter.leg_convexity_floor: must be in [0, 1], got -0.1");
  ExpectConfigError("segmenter:\n  line_split_range_fraction: 1.5\n",
                    "line_split_range_fraction");
  ExpectConfigError("segmenter:\n  depth_edge_m: 0\n", "depth_edge_m");
}

// Every key of an earlier version is an error that names its new key.
TEST(SegmenterStageTest, RenamedKeysNameTheirNewKey) {
  ASSERT_EQ(RenamedSegmenterKeys().size(), 6u);
  for (const RenamedKey& r : RenamedSegmenterKeys()) {
    std::string what;
    try {
      const std::string yaml = "segmenter:\n  " + r.old_key + ": 0.5\n";
      ReadSegmenterOptions(Config::FromString(yaml, "old.yaml").Child("segmenter"));
    } catch (const ConfigError& e) {
      what = e.what();
    }
    EXPECT_NE(what.find("old.yaml:2: segmenter." + r.old_key + ": renamed to " + r.new_key),
              std::string::npos)
        << what;
  }
}

// The schema names every key once, the reader reads every one of them (a file that sets every
// key to its default is accepted and gives the defaults, bit for bit), and docs/perception.md
// carries the generated table and the migration note.
TEST(SegmenterStageTest, EveryKeyOfTheSchemaIsReadAndDocumented) {
  const std::string table = SegmenterOptionsTable();
  const std::vector<slammtt::testing::OptionsTableRow> rows = slammtt::testing::ParseOptionsTable(table);
  ASSERT_EQ(rows.size(), 40u) << table;
  EXPECT_TRUE(slammtt::testing::KeysAreUnique(rows)) << "a key twice";
  for (const RenamedKey& r : RenamedSegmenterKeys()) {
    const auto named = [&](const std::string& key) {
      return std::any_of(rows.begin(), rows.end(),
                         [&](const slammtt::testing::OptionsTableRow& row) { return row.key == key; });
    };
    EXPECT_TRUE(named(r.new_key)) << r.new_key;
    EXPECT_FALSE(named(r.old_key)) << r.old_key;
  }
  const SegmenterOptions o = ReadSegmenterOptions(
      Config::FromString(slammtt::testing::SectionOfDefaults("segmenter", rows), "every.yaml")
          .Child("segmenter"));
  const SegmenterOptions d;
  EXPECT_EQ(o.lambda_rad, d.lambda_rad);
  EXPECT_EQ(o.bearing_sigma_rad, d.bearing_sigma_rad);
  EXPECT_EQ(o.duplicate_angle_tolerance_rad, d.duplicate_angle_tolerance_rad);
  EXPECT_TRUE(std::isinf(o.max_range_m));
  EXPECT_EQ(o.centre_rule, d.centre_rule);
  EXPECT_EQ(o.leg.convexity_floor, d.leg.convexity_floor);
  EXPECT_EQ(o.person.single_leg_offset_sigma_m, d.person.single_leg_offset_sigma_m);
  EXPECT_EQ(o.person.single_leg_open_edge_step, d.person.single_leg_open_edge_step);
  EXPECT_EQ(o.person.hidden_leg_centre, d.person.hidden_leg_centre);
  EXPECT_EQ(o.person.single_leg_surface_clearance_m, d.person.single_leg_surface_clearance_m);
  EXPECT_EQ(o.person.separate_dropout_pieces, d.person.separate_dropout_pieces);
  EXPECT_EQ(o.person.single_leg_open_edge_max_points, d.person.single_leg_open_edge_max_points);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/perception.md");
  ASSERT_FALSE(docs.empty()) << "docs/perception.md is part of the checkout";
  EXPECT_NE(docs.find(table), std::string::npos)
      << "docs/perception.md: replace the options table by `slammtt-segmenter --options-table`";
  for (const RenamedKey& r : RenamedSegmenterKeys()) {
    EXPECT_NE(docs.find("| `" + r.old_key + "` | `" + r.new_key + "` |"), std::string::npos)
        << "docs/perception.md, Migration: " << r.old_key;
  }
}

// An absent section gives exactly the pure library's defaults (the stage and the tests that
// build SegmenterOptions{} segment alike).
TEST(SegmenterStageTest, AbsentKeysKeepTheDefaultsBitForBit) {
  const SegmenterOptions o = ReadSegmenterOptions(Config());
  const SegmenterOptions d;
  EXPECT_EQ(o.lambda_rad, d.lambda_rad);
  EXPECT_EQ(o.max_beam_gap_rad, d.max_beam_gap_rad);
  EXPECT_EQ(o.duplicate_angle_tolerance_rad, d.duplicate_angle_tolerance_rad);
  EXPECT_EQ(o.bearing_sigma_rad, d.bearing_sigma_rad);
  EXPECT_EQ(o.leg_threshold, d.leg_threshold);
  EXPECT_EQ(o.max_range_m, d.max_range_m);
  // 0 is "no limit" in the configuration.
  const SegmenterOptions unlimited = ReadSegmenterOptions(
      Config::FromString("segmenter:\n  max_range_m: 0\n", "s.yaml").Child("segmenter"));
  EXPECT_TRUE(std::isinf(unlimited.max_range_m));
}

// A wall behind a person on two legs: FEATURES carries the wall as a line, both legs as point
// features with their leg-likeness, and one person whose leg_index names them.
TEST(SegmenterStageTest, PublishesLinesAndPeople) {
  std::mt19937_64 rng(2);
  const testing_support::TestScan scan = testing_support::CastScene(
      {{2.0, 0.12, 0.06}, {2.0, -0.12, 0.06}}, {{4.0, -3.0, 4.0, 3.0}},
      EvenAngles(-M_PI, 2.0 * M_PI, 1024, true), 12.0, 0.01, 0.0, &rng);
  const std::vector<uint8_t> bytes = Encode(testing_support::ScanMessage(scan, 1000, 1));
  SegmenterStage stage = MakeStage();
  CapturingSink sink;
  stage.Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), sink);
  ASSERT_EQ(sink.messages.size(), 2u);
  slammtt_msgs::features_t features;
  ASSERT_TRUE(Decode(sink.messages[0].bytes.data(),
                     static_cast<int>(sink.messages[0].bytes.size()), &features));
  ASSERT_EQ(features.num_lines, 1);
  EXPECT_NEAR(features.lines[0].rho_m, 4.0, 0.02);
  EXPECT_NEAR(features.lines[0].alpha_rad, 0.0, 0.01);
  EXPECT_GT(features.lines[0].rho_var_m2, 0.0);
  EXPECT_GT(features.lines[0].alpha_var_rad2, 0.0);
  EXPECT_GT(features.lines[0].num_points, 100);
  EXPECT_NEAR(features.lines[0].first_x_m, 4.0, 0.05);
  ASSERT_EQ(features.num_features, 2);
  for (const slammtt_msgs::feature_t& f : features.features) {
    EXPECT_GE(f.leg_likeness, 0.65);
    EXPECT_LE(f.leg_likeness, 1.0);
  }
  ASSERT_EQ(features.num_people, 1);
  const slammtt_msgs::person_feature_t& person = features.people[0];
  EXPECT_EQ(person.num_legs, 2);
  EXPECT_EQ(std::min(person.leg_index[0], person.leg_index[1]), 0);
  EXPECT_EQ(std::max(person.leg_index[0], person.leg_index[1]), 1);
  EXPECT_NEAR(person.range_m, 2.0, 0.05);  // midpoint of the legs' centres
  EXPECT_NEAR(person.bearing_rad, 0.0, 0.02);
  EXPECT_GT(person.confidence, 0.5);
  EXPECT_GT(person.range_var_m2, 0.0);
}

TEST(SegmenterStageTest, FactoryUsesTheStackConfigurationAndChannelNames) {
  CommandLine command_line("test", "", "");
  AddStandardOptions(&command_line);
  const char* argv[] = {"test", "--channel", "laser_scan=SCAN_SIM", "--channel",
                        "features=FEATURES_SIM"};
  ASSERT_TRUE(command_line.Parse(5, argv));
  ProcessSettings settings = LoadProcessSettings(command_line);
  settings.config = Config::FromString("segmenter:\n  min_points: 200\n");
  const std::unique_ptr<Stage> stage = CreateSegmenterStage(settings);
  ASSERT_EQ(stage->InputChannels(), std::vector<std::string>{"SCAN_SIM"});
  CapturingSink sink;
  const std::vector<uint8_t> bytes = Encode(MakeScanMessage(1, 1));
  stage->Handle("LASER_SCAN", bytes.data(), static_cast<int>(bytes.size()), sink);
  EXPECT_TRUE(sink.messages.empty());  // not its channel any more
  stage->Handle("SCAN_SIM", bytes.data(), static_cast<int>(bytes.size()), sink);
  ASSERT_EQ(sink.messages.size(), 2u);
  EXPECT_EQ(sink.messages[0].channel, "FEATURES_SIM");
  EXPECT_EQ(sink.messages[1].channel, "STAGE_TIMING");
  slammtt_msgs::features_t features;
  ASSERT_TRUE(Decode(sink.messages[0].bytes.data(),
                     static_cast<int>(sink.messages[0].bytes.size()), &features));
  EXPECT_EQ(features.num_features, 0);  // min_points 200 from the configuration

  settings.config = Config::FromString("segmenter:\n  typo: 1\n");
  EXPECT_THROW(CreateSegmenterStage(settings), ConfigError);
}

}  // namespace
}  // namespace slammtt
