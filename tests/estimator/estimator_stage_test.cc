// The stage adapter: configuration, messages in and out, timing, bad messages, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "estimator/estimator_stage.h"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/smoother_input_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "tests/support/options_table.h"

namespace slammtt {
namespace {

struct Published {
  std::string channel;
  std::vector<uint8_t> bytes;
};

class RecordingSink : public MessageSink {
 public:
  void Publish(const std::string& channel, const void* data, int size) override {
    const auto* bytes = static_cast<const uint8_t*>(data);
    messages.push_back({channel, std::vector<uint8_t>(bytes, bytes + size)});
  }
  template <class Msg>
  Msg Get(size_t k) const {
    Msg message;
    EXPECT_TRUE(Decode(messages.at(k).bytes.data(), static_cast<int>(messages.at(k).bytes.size()),
                       &message));
    return message;
  }
  std::vector<Published> messages;
};

std::vector<uint8_t> OdometryBytes(int64_t utime, double x_m, double linear_mps) {
  slammtt_msgs::odometry_t m{};
  m.utime = utime;
  m.x_m = x_m;
  m.linear_velocity_mps = linear_mps;
  return Encode(m);
}

std::vector<uint8_t> FeaturesBytes(int64_t utime, const std::vector<std::pair<double, double>>& rb) {
  slammtt_msgs::features_t m{};
  m.utime = utime;
  for (const auto& [range, bearing] : rb) {
    slammtt_msgs::feature_t f{};
    f.range_m = range;
    f.bearing_rad = bearing;
    f.range_var_m2 = 0.04;
    f.bearing_var_rad2 = 0.0012;
    m.features.push_back(f);
  }
  m.num_features = static_cast<int32_t>(m.features.size());
  return Encode(m);
}

void Feed(EstimatorStage* stage, const std::string& channel, const std::vector<uint8_t>& bytes,
          MessageSink& out) {
  stage->Handle(channel, bytes.data(), static_cast<int>(bytes.size()), out);
}

TEST(EstimatorOptionsTest, DefaultsAndKeys) {
  const EstimatorStageOptions defaults = ReadEstimatorOptions(Config());
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_EQ(defaults.estimator.mode, AssociationMode::kMlRansac);
  EXPECT_DOUBLE_EQ(defaults.estimator.tracks.prune_unseen_s, 3.5);
  EXPECT_DOUBLE_EQ(defaults.estimator.ransac.success_probability, 0.99);
  const Config config = Config::FromString(
      "estimator:\n"
      "  mode: static_nn\n"
      "  seed: 42\n"
      "  sensor_forward_m: 0.1\n"
      "  field_of_view_deg: 180\n"
      "  default_bearing_sigma_deg: 1\n"
      "  initial_pose: [1, 2, 90]\n"
      "  level3: false\n"
      "  ransac_max_hypotheses: 50\n"
      "  max_static_updates_per_scan: 7\n"
      "  tracks_confirm_hits: 4\n"
      "  classifier_moving_chi2: 10\n"
      "  odometry_noise_rotation_var_per_m: 0.002\n"
      "  extrapolation_turn_sigma_degps: 90\n",
      "test.yaml");
  const EstimatorStageOptions o = ReadEstimatorOptions(config.Child("estimator"));
  EXPECT_EQ(o.seed, 42u);
  EXPECT_EQ(o.estimator.mode, AssociationMode::kStaticNearestNeighbour);
  EXPECT_DOUBLE_EQ(o.estimator.sensor.forward_m, 0.1);
  EXPECT_NEAR(o.estimator.field_of_view_rad, M_PI, 1e-12);
  EXPECT_NEAR(o.estimator.default_bearing_sigma_rad, M_PI / 180.0, 1e-12);
  EXPECT_NEAR(o.estimator.initial_pose(2), M_PI / 2.0, 1e-12);
  EXPECT_FALSE(o.estimator.level3);
  EXPECT_EQ(o.estimator.ransac.max_hypotheses, 50);
  EXPECT_EQ(o.estimator.max_static_updates_per_scan, 7);
  EXPECT_EQ(o.estimator.tracks.confirm_hits, 4);
  EXPECT_EQ(o.estimator.classifier.moving_chi2, 10.0);
  EXPECT_EQ(o.estimator.odometry_noise.rotation_var_per_m, 0.002);
  EXPECT_EQ(o.estimator.extrapolation_turn_sigma_radps, 90.0 * M_PI / 180.0);
}

TEST(EstimatorOptionsTest, MistakesNameTheKey) {
  auto error = [](const std::string& yaml) -> std::string {
    try {
      ReadEstimatorOptions(Config::FromString(yaml, "stack.yaml").Child("estimator"));
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error("estimator:\n  gate_d11: 3\n").find("gate_d11"), std::string::npos);
  EXPECT_NE(error("estimator:\n  mode: magic\n").find("mode"), std::string::npos);
  EXPECT_NE(
      error("estimator:\n  ransac_max_hypotheses: 0\n")
          .find("stack.yaml:2: estimator.ransac_max_hypotheses: must be in [1, 1e+06], got 0"),
      std::string::npos);
  EXPECT_NE(error("estimator:\n  gate_d1_chi2: 20\n  gate_d2_chi2: 10\n").find("gate_d2_chi2"),
            std::string::npos);
  EXPECT_NE(error("estimator:\n  initial_pose: [1, 2]\n").find("initial_pose"), std::string::npos);
  EXPECT_NE(error("estimator:\n  default_range_sigma_m: -1\n").find("must be > 0, got -1"),
            std::string::npos);
  EXPECT_NE(error("estimator:\n  field_of_view_deg: 400\n").find("must be in (0, 360]"),
            std::string::npos);
  EXPECT_NE(error("estimator:\n  max_static_updates_per_scan: -1\n")
                .find("max_static_updates_per_scan"),
            std::string::npos);
  EXPECT_NE(error("estimator:\n  tracks_confirm_hits: two\n").find("tracks_confirm_hits"),
            std::string::npos);
}

// Every key of an earlier version is an error that names its new key, and the new key is read.
TEST(EstimatorOptionsTest, RenamedKeysNameTheirNewKey) {
  ASSERT_GE(RenamedEstimatorKeys().size(), 30u);
  for (const RenamedKey& r : RenamedEstimatorKeys()) {
    std::string what;
    try {
      const std::string yaml = "estimator:\n  " + r.old_key + ": 1\n";
      ReadEstimatorOptions(Config::FromString(yaml, "old.yaml").Child("estimator"));
    } catch (const ConfigError& e) {
      what = e.what();
    }
    EXPECT_NE(what.find("estimator." + r.old_key + ": renamed to " + r.new_key), std::string::npos)
        << what;
  }
}

// The schema names every key once, the reader reads every one of them (a file that sets every
// key to its default is accepted and gives the defaults), and docs/estimator.md carries the
// generated table and the migration note.
TEST(EstimatorOptionsTest, EveryKeyOfTheSchemaIsReadAndDocumented) {
  const std::string table = EstimatorStageOptionsTable();
  const std::vector<slammtt::testing::OptionsTableRow> rows = slammtt::testing::ParseOptionsTable(table);
  ASSERT_GE(rows.size(), 60u);
  EXPECT_TRUE(slammtt::testing::KeysAreUnique(rows)) << "a key twice";
  const EstimatorStageOptions o = ReadEstimatorOptions(
      Config::FromString(slammtt::testing::SectionOfDefaults("estimator", rows), "every.yaml")
          .Child("estimator"));
  EXPECT_EQ(o.estimator.tracks.confirm_hits, EstimatorOptions().tracks.confirm_hits);
  EXPECT_EQ(o.estimator.gate_d1_chi2, EstimatorOptions().gate_d1_chi2);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/estimator.md");
  ASSERT_FALSE(docs.empty()) << "docs/estimator.md is part of the checkout";
  EXPECT_NE(docs.find(table), std::string::npos)
      << "docs/estimator.md: replace the options table by `slammtt-estimator --options-table`";
  for (const RenamedKey& r : RenamedEstimatorKeys()) {
    EXPECT_NE(docs.find("| `" + r.old_key + "` | `" + r.new_key + "` |"), std::string::npos)
        << "docs/estimator.md, Migration: " << r.old_key;
  }
}

TEST(EstimatorOptionsTest, TheEstimatorRefusesUnusableOptions) {
  EstimatorOptions options;
  EXPECT_NO_THROW(Estimator{options});
  options.tracks.confirm_hits = 0;
  EXPECT_THROW(Estimator{options}, std::invalid_argument);
  options = EstimatorOptions();
  options.gate_d2_chi2 = options.gate_d1_chi2;
  try {
    Estimator estimator(options);
    ADD_FAILURE() << "accepted gate_d2_chi2 = gate_d1_chi2";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gate_d2_chi2"), std::string::npos) << e.what();
  }
  options = EstimatorOptions();
  options.field_of_view_rad = std::nan("");
  EXPECT_THROW(Estimator{options}, std::invalid_argument);
}

// Two legs of a person at (2, +-0.1) in the sensor frame, a post at 4 m ahead, and a person
// feature pairing the legs: one person measurement and the post; without person features, the
// three points.
slammtt_msgs::features_t PersonAndPost() {
  slammtt_msgs::features_t m{};
  m.utime = 1000;
  for (const auto& [x, y, width] : {std::tuple{2.0, 0.1, 0.1}, std::tuple{2.0, -0.1, 0.12},
                                    std::tuple{4.0, 0.0, 0.2}}) {
    slammtt_msgs::feature_t f{};
    f.range_m = std::hypot(x, y);
    f.bearing_rad = std::atan2(y, x);
    f.width_m = width;
    f.range_var_m2 = 0.0004;
    f.bearing_var_rad2 = 0.0001;
    m.features.push_back(f);
  }
  m.num_features = 3;
  slammtt_msgs::person_feature_t p{};
  p.range_m = 2.0;
  p.bearing_rad = 0.0;
  p.range_var_m2 = 0.01;
  p.bearing_var_rad2 = 0.002;
  p.num_legs = 2;
  p.leg_index[0] = 0;
  p.leg_index[1] = 1;
  p.confidence = 0.9;
  m.people.push_back(p);
  m.num_people = 1;
  return m;
}

TEST(ScanInputFromFeaturesTest, APersonReplacesItsLegs) {
  const ScanInput scan = ScanInputFromFeatures(PersonAndPost(), true);
  ASSERT_EQ(scan.features.size(), 2u);
  EXPECT_DOUBLE_EQ(scan.features[0].range_m, 2.0);
  EXPECT_DOUBLE_EQ(scan.features[0].range_var_m2, 0.01);
  EXPECT_NEAR(scan.features[0].width_m, 0.2 + 0.11, 1e-12);  // leg span + mean leg width
  EXPECT_DOUBLE_EQ(scan.features[1].range_m, 4.0);
  const ScanInput legs = ScanInputFromFeatures(PersonAndPost(), false);
  ASSERT_EQ(legs.features.size(), 3u);
  EXPECT_NEAR(legs.features[0].bearing_rad, std::atan2(0.1, 2.0), 1e-12);
}

TEST(ScanInputFromFeaturesTest, BadOrSharedLegIndicesAreIgnored) {
  slammtt_msgs::features_t m = PersonAndPost();
  slammtt_msgs::person_feature_t second = m.people[0];
  second.range_m = 3.0;
  second.num_legs = 2;
  second.leg_index[0] = 1;   // already the first person's leg
  second.leg_index[1] = 17;  // no such feature
  m.people.push_back(second);
  m.people[0].leg_index[1] = -5;  // the first person keeps leg 0 only
  m.num_people = 2;
  const ScanInput scan = ScanInputFromFeatures(m, true);
  // Person 1 (leg 0), person 2 (leg 1), the post: every point used once.
  ASSERT_EQ(scan.features.size(), 3u);
  EXPECT_DOUBLE_EQ(scan.features[0].width_m, 0.1);
  EXPECT_DOUBLE_EQ(scan.features[1].range_m, 3.0);
  EXPECT_DOUBLE_EQ(scan.features[1].width_m, 0.12);
  EXPECT_DOUBLE_EQ(scan.features[2].range_m, 4.0);
}

TEST(EstimatorStageTest, WithSmootherFirstSightingsTheStartingSightingsGoToTheSmoother) {
  EstimatorStageOptions options;
  options.estimator.smoother_first_sightings = true;
  EstimatorStage stage(options, Channels());
  RecordingSink out;
  Feed(&stage, "ODOMETRY", OdometryBytes(0, 0.0, 0.5), out);
  Feed(&stage, "ODOMETRY", OdometryBytes(100000, 0.05, 0.5), out);
  Feed(&stage, "FEATURES", FeaturesBytes(100000, {{5.0, 0.2}, {7.0, -0.4}}), out);
  ASSERT_EQ(out.messages.size(), 6u);
  const auto tracks = out.Get<slammtt_msgs::tracks_t>(2);
  ASSERT_EQ(tracks.num_tracks, 2);
  // Both features start objects; their starting sightings go to the smoother, tentative, under
  // the new tracks' ids.
  const auto smoother_input = out.Get<slammtt_msgs::smoother_input_t>(3);
  ASSERT_EQ(smoother_input.num_observations, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(smoother_input.observations[k].landmark_id, tracks.tracks[k].id);
    EXPECT_TRUE(smoother_input.observations[k].tentative);
  }
}

TEST(EstimatorStageTest, PublishesEveryOutputWithTheFeaturesUtime) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  EXPECT_EQ(stage.Name(), "estimator");
  EXPECT_EQ(stage.InputChannels(),
            (std::vector<std::string>{"ODOMETRY", "FEATURES", "LASER_GEOMETRY"}));
  RecordingSink out;
  Feed(&stage, "ODOMETRY", OdometryBytes(0, 0.0, 0.5), out);
  Feed(&stage, "ODOMETRY", OdometryBytes(100000, 0.05, 0.5), out);
  EXPECT_TRUE(out.messages.empty());
  Feed(&stage, "FEATURES", FeaturesBytes(100000, {{5.0, 0.2}, {7.0, -0.4}}), out);
  ASSERT_EQ(out.messages.size(), 6u);
  EXPECT_EQ(out.messages[0].channel, "POSE");
  EXPECT_EQ(out.messages[1].channel, "MAP");
  EXPECT_EQ(out.messages[2].channel, "TRACKS");
  EXPECT_EQ(out.messages[3].channel, "SMOOTHER_INPUT");
  EXPECT_EQ(out.messages[4].channel, "ESTIMATOR_STATUS");
  EXPECT_EQ(out.messages[5].channel, "STAGE_TIMING");
  const auto pose = out.Get<slammtt_msgs::pose_t>(0);
  EXPECT_EQ(pose.utime, 100000);
  EXPECT_NEAR(pose.x_m, 0.05, 1e-9);
  EXPECT_EQ(out.Get<slammtt_msgs::map_t>(1).utime, 100000);
  EXPECT_EQ(out.Get<slammtt_msgs::map_t>(1).num_landmarks, 0);  // nothing static yet
  const auto tracks = out.Get<slammtt_msgs::tracks_t>(2);
  EXPECT_EQ(tracks.utime, 100000);
  ASSERT_EQ(tracks.num_tracks, 2);
  EXPECT_EQ(tracks.tracks[0].object_class, static_cast<int8_t>(slammtt_msgs::track_t::CLASS_UNDECIDED));
  EXPECT_FALSE(tracks.tracks[0].confirmed);
  EXPECT_EQ(tracks.tracks[0].first_seen_utime, 100000);
  // The first scan: no motion from a previous one; both features start objects (no
  // association yet), whose starting sightings the smoother does not get by default
  // (smoother_first_sightings; the next test).
  const auto smoother_input = out.Get<slammtt_msgs::smoother_input_t>(3);
  EXPECT_EQ(smoother_input.utime, 100000);
  EXPECT_FALSE(smoother_input.continues);
  EXPECT_EQ(smoother_input.num_observations, 0);
  EXPECT_NEAR(smoother_input.x_m, 0.05, 1e-9);
  const auto status = out.Get<slammtt_msgs::estimator_status_t>(4);
  EXPECT_EQ(status.utime, 100000);
  EXPECT_EQ(status.scans_processed, 1);
  EXPECT_EQ(status.odometry_processed, 2);
  EXPECT_EQ(status.num_tentative, 2);
  // The odometry heading drift state: nothing has measured it yet, so it is still its prior
  // (mean 0, sigma the configured one plus 0.05 m of random walk).
  const EstimatorOptions defaults;
  const double prior_sigma = defaults.heading_drift_sigma_rad_per_m;
  EXPECT_EQ(status.heading_drift_rad_per_m, 0.0);
  EXPECT_EQ(status.restarts, 0);
  EXPECT_EQ(status.time_jumps_rejected, 0);
  EXPECT_EQ(status.features_over_cap, 0);
  EXPECT_EQ(status.state_recoveries, 0);
  EXPECT_NEAR(status.heading_drift_sigma_rad_per_m,
              std::sqrt(prior_sigma * prior_sigma + 0.05 * defaults.heading_drift_walk_var_per_m),
              1e-12);
  const auto timing = out.Get<slammtt_msgs::stage_timing_t>(5);
  EXPECT_EQ(timing.utime, 100000);
  EXPECT_EQ(timing.stage, "estimator");
  EXPECT_EQ(timing.substage, (std::vector<std::string>{"predict", "gating", "level1", "ransac",
                                                        "level2_3", "track_management"}));
  EXPECT_EQ(timing.counter_name,
            (std::vector<std::string>{"features", "objects", "hypotheses", "updates",
                                      "updates_skipped", "lines", "line_updates", "new_lines",
                                      "features_over_cap", "ransac_pair_tests",
                                      "ransac_budget_cut", "state_recovered", "archived"}));
  EXPECT_EQ(timing.counter_value[0], 2);
  EXPECT_EQ(timing.counter_value[1], 2);
  EXPECT_EQ(timing.counter_value[3], 0);  // two new objects, nothing to update yet
  EXPECT_EQ(timing.counter_value[4], 0);
}

TEST(EstimatorStageTest, StaticObjectsReachTheMap) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  RecordingSink out;
  for (int k = 0; k <= 60; ++k) {
    const int64_t t = 100000 * k;
    Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.0, 0.0), out);
    Feed(&stage, "FEATURES", FeaturesBytes(t, {{5.0, 0.2}, {7.0, -0.4}}), out);
  }
  const auto map = out.Get<slammtt_msgs::map_t>(out.messages.size() - 5);
  ASSERT_EQ(map.num_landmarks, 2);
  EXPECT_NEAR(map.landmarks[0].x_m, 5.0 * std::cos(0.2), 0.05);
  EXPECT_NEAR(map.landmarks[0].y_m, 5.0 * std::sin(0.2), 0.05);
  const auto tracks = out.Get<slammtt_msgs::tracks_t>(out.messages.size() - 4);
  EXPECT_EQ(tracks.tracks[1].object_class, static_cast<int8_t>(slammtt_msgs::track_t::CLASS_STATIC));
  EXPECT_TRUE(tracks.tracks[1].confirmed);
  EXPECT_EQ(tracks.tracks[1].vx_mps, 0.0);
  EXPECT_EQ(tracks.tracks[1].covariance[10], 0.0);  // no velocity states
}

// A person who stands still (the person feature of PersonAndPost, 2 m ahead, at every scan)
// and a post: both become STATIC; the person is a track of kind PERSON that never enters the
// map, the post is the map's one landmark. Every track is measured at every scan, so it
// coasts 0 s and, once confirmed, is reported; the person feature marks the person track.
// The track of kind PERSON in `tracks` (scan `k` of a test, for the failure message); a failure
// and an empty track without one.
slammtt_msgs::track_t PersonTrackOf(const slammtt_msgs::tracks_t& tracks, int k) {
  for (const slammtt_msgs::track_t& t : tracks.tracks) {
    if (t.kind == slammtt_msgs::track_t::KIND_PERSON) return t;
  }
  ADD_FAILURE() << "no person track at scan " << k;
  return slammtt_msgs::track_t{};
}

// The TRACKS of scans 0..last of a robot standing at the origin (ODOMETRY and FEATURES every
// 0.1 s), FEATURES of scan k from features_of_scan(k) with its utime set.
std::vector<slammtt_msgs::tracks_t> TracksOfAStandingRobot(
    const EstimatorStageOptions& options, int last,
    const std::function<slammtt_msgs::features_t(int)>& features_of_scan) {
  EstimatorStage stage(options, Channels());
  RecordingSink out;
  std::vector<slammtt_msgs::tracks_t> tracks;
  for (int k = 0; k <= last; ++k) {
    const int64_t t = 100000 * k;
    Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.0, 0.0), out);
    slammtt_msgs::features_t m = features_of_scan(k);
    m.utime = t;
    Feed(&stage, "FEATURES", Encode(m), out);
    tracks.push_back(out.Get<slammtt_msgs::tracks_t>(out.messages.size() - 4));
  }
  return tracks;
}

TEST(EstimatorStageTest, AStandingPersonIsAStaticPersonTrackNeverInTheMap) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  RecordingSink out;
  for (int k = 0; k <= 60; ++k) {
    const int64_t t = 100000 * k;
    Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.0, 0.0), out);
    slammtt_msgs::features_t m = PersonAndPost();
    m.utime = t;
    Feed(&stage, "FEATURES", Encode(m), out);
  }
  const auto map = out.Get<slammtt_msgs::map_t>(out.messages.size() - 5);
  const auto tracks = out.Get<slammtt_msgs::tracks_t>(out.messages.size() - 4);
  ASSERT_EQ(tracks.num_tracks, 2);
  using Track = slammtt_msgs::track_t;
  const Track& person = tracks.tracks[0];
  const Track& post = tracks.tracks[1];
  EXPECT_EQ(person.kind, static_cast<int8_t>(Track::KIND_PERSON));
  EXPECT_EQ(person.object_class, static_cast<int8_t>(Track::CLASS_STATIC));
  EXPECT_NEAR(person.x_m, 2.0, 0.05);
  EXPECT_EQ(post.kind, static_cast<int8_t>(Track::KIND_OTHER));
  EXPECT_EQ(post.object_class, static_cast<int8_t>(Track::CLASS_STATIC));
  for (const Track& t : tracks.tracks) {
    EXPECT_TRUE(t.measured);
    EXPECT_EQ(t.coasting_s, 0.0);
    EXPECT_TRUE(t.confirmed);
    EXPECT_TRUE(t.reported);
    EXPECT_EQ(t.last_seen_utime, tracks.utime);
  }
  ASSERT_EQ(map.num_landmarks, 1);
  EXPECT_EQ(map.landmarks[0].id, post.id);
}

// The person of PersonAndPost is seen for 20 scans and then no more (the post still is): its
// track coasts; at 0.1 s per scan it is measured-and-reported at the last scan with the person,
// still confirmed but no longer reported once it has coasted longer than
// tracks_report_measured_within_s (0.5 s), and coasting_s says for how long.
TEST(EstimatorStageTest, ACoastingTrackSaysSoAndIsNotReported) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  RecordingSink out;
  std::vector<slammtt_msgs::tracks_t> tracks;
  for (int k = 0; k <= 30; ++k) {
    const int64_t t = 100000 * k;
    Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.0, 0.0), out);
    slammtt_msgs::features_t m = PersonAndPost();
    m.utime = t;
    if (k >= 20) {  // the post alone
      m.features = {m.features[2]};
      m.num_features = 1;
      m.people.clear();
      m.num_people = 0;
    }
    Feed(&stage, "FEATURES", Encode(m), out);
    tracks.push_back(out.Get<slammtt_msgs::tracks_t>(out.messages.size() - 4));
  }
  auto person_at = [&](int k) { return PersonTrackOf(tracks[static_cast<size_t>(k)], k); };
  EXPECT_TRUE(person_at(19).measured);
  EXPECT_TRUE(person_at(19).reported);
  EXPECT_FALSE(person_at(22).measured);
  EXPECT_NEAR(person_at(22).coasting_s, 0.3, 1e-9);
  EXPECT_TRUE(person_at(22).reported);  // 0.3 s <= 0.5 s
  EXPECT_NEAR(person_at(25).coasting_s, 0.6, 1e-9);
  EXPECT_FALSE(person_at(25).reported);
  EXPECT_TRUE(person_at(25).confirmed);  // a static track: its existence is not in doubt
}

// The person of PersonAndPost seen as one leg only (the person feature keeps leg 0, leg 1 is
// not there) for 15 scans, then as two legs paired: with the defaults its track is reported as
// a person from its confirmation on; with people_report_min_pair_hits 1 it is a person track
// that is not reported until its first scan of two legs paired (people.h, ShowsAPerson). The
// post is reported either way.
TEST(EstimatorStageTest, APersonSeenAsOneLegIsReportedOnlyOnceItsLegsWerePairedWhenAsked) {
  for (const int min_pair_hits : {0, 1}) {
    SCOPED_TRACE(min_pair_hits);
    EstimatorStageOptions options;
    ASSERT_EQ(options.estimator.people.report_min_pair_hits, 0);  // off by default
    options.estimator.people.report_min_pair_hits = min_pair_hits;
    const std::vector<slammtt_msgs::tracks_t> tracks =
        TracksOfAStandingRobot(options, 20, [](int k) {
          slammtt_msgs::features_t m = PersonAndPost();
          if (k < 15) {  // one leg: leg 1 was not seen
            m.features = {m.features[0], m.features[2]};
            m.num_features = 2;
            m.people[0].num_legs = 1;
            m.people[0].leg_index[1] = -1;
            m.people[0].range_m = std::hypot(2.0, 0.1);
            m.people[0].bearing_rad = std::atan2(0.1, 2.0);
            m.people[0].confidence = 0.4;
          }
          return m;
        });
    using Track = slammtt_msgs::track_t;
    auto person_at = [&](int k) { return PersonTrackOf(tracks[static_cast<size_t>(k)], k); };
    for (int k = 2; k < 15; ++k) {
      EXPECT_TRUE(person_at(k).confirmed) << k;
      EXPECT_TRUE(person_at(k).measured) << k;
      EXPECT_EQ(person_at(k).reported, min_pair_hits == 0) << k;
    }
    EXPECT_EQ(person_at(14).id, person_at(15).id);
    for (int k = 15; k <= 20; ++k) EXPECT_TRUE(person_at(k).reported) << k;
    for (const Track& t : tracks.back().tracks) {
      if (t.kind == Track::KIND_OTHER) {
        EXPECT_TRUE(t.reported);
      }
    }
  }
}

// The person of PersonAndPost moved 5 m farther away, to 7 m (its legs with it), seen at every
// scan: beyond people_report_far_m (6 m) its track is confirmed at its 2nd hit but reported
// only from its 6th (people_report_far_min_hits; people.h, ShowsAPerson); at 2 m, from its
// 2nd. With people_report_far_m 0, at 7 m too.
TEST(EstimatorStageTest, AFarPersonIsReportedFromItsSixthHit) {
  for (const double far_m : {6.0, 0.0}) {
    for (const double range_m : {7.0, 2.0}) {
      SCOPED_TRACE(::testing::Message() << far_m << " " << range_m);
      EstimatorStageOptions options;
      ASSERT_EQ(options.estimator.people.report_far_m, 6.0);  // on by default
      ASSERT_EQ(options.estimator.people.report_far_min_hits, 6);
      options.estimator.people.report_far_m = far_m;
      const std::vector<slammtt_msgs::tracks_t> tracks =
          TracksOfAStandingRobot(options, 8, [range_m](int) {
            slammtt_msgs::features_t m = PersonAndPost();
            for (int leg = 0; leg < 2; ++leg) {
              slammtt_msgs::feature_t& f = m.features[static_cast<size_t>(leg)];
              const double y = leg == 0 ? 0.1 : -0.1;
              f.range_m = std::hypot(range_m, y);
              f.bearing_rad = std::atan2(y, range_m);
            }
            m.people[0].range_m = range_m;
            return m;
          });
      auto person_at = [&](int k) { return PersonTrackOf(tracks[static_cast<size_t>(k)], k); };
      const bool held_back = far_m > 0.0 && range_m > far_m;
      for (int k = 1; k <= 8; ++k) {  // scan k: hit k + 1
        EXPECT_TRUE(person_at(k).confirmed) << k;
        EXPECT_EQ(person_at(k).hits, k + 1) << k;
        EXPECT_EQ(person_at(k).reported, !held_back || k + 1 >= 6) << k;
      }
    }
  }
}

// A wall 3 m ahead (x = 3, from y = -1 to 2) and one 2 m to the left (y = 2), as line features
// of a robot standing at the origin.
std::vector<uint8_t> WallFeaturesBytes(int64_t utime) {
  slammtt_msgs::features_t m{};
  m.utime = utime;
  slammtt_msgs::line_feature_t ahead{};
  ahead.rho_m = 3.0;
  ahead.alpha_rad = 0.0;
  ahead.rho_var_m2 = 1e-4;
  ahead.alpha_var_rad2 = 1e-5;
  ahead.first_x_m = 3.0;
  ahead.first_y_m = -1.0;
  ahead.last_x_m = 3.0;
  ahead.last_y_m = 2.0;
  ahead.num_points = 40;
  slammtt_msgs::line_feature_t left = ahead;
  left.rho_m = 2.0;
  left.alpha_rad = M_PI / 2;
  left.first_x_m = 3.0;
  left.first_y_m = 2.0;
  left.last_x_m = -1.0;
  left.last_y_m = 2.0;
  m.lines = {ahead, left};
  m.num_lines = 2;
  return Encode(m);
}

TEST(EstimatorStageTest, LineFeaturesBecomeTheLinesOfTheMap) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  RecordingSink out;
  // Candidates for lines_confirm_scans scans, then landmarks seen twice more.
  const int scans = EstimatorOptions().lines.confirm_scans + 2;
  for (int k = 0; k < scans; ++k) {
    const int64_t t = 100000 * (k + 1);
    Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.0, 0.0), out);
    Feed(&stage, "FEATURES", WallFeaturesBytes(t), out);
  }
  const auto map = out.Get<slammtt_msgs::map_t>(out.messages.size() - 5);
  EXPECT_EQ(map.num_landmarks, 0);
  ASSERT_EQ(map.num_lines, 2);
  EXPECT_NEAR(map.lines[0].rho_m, 3.0, 1e-6);
  EXPECT_NEAR(map.lines[0].alpha_rad, 0.0, 1e-6);
  EXPECT_NEAR(map.lines[1].rho_m, 2.0, 1e-6);
  EXPECT_NEAR(map.lines[1].alpha_rad, M_PI / 2, 1e-6);
  EXPECT_EQ(map.lines[0].hits, 3);
  EXPECT_NEAR(map.lines[0].from_y_m, -1.0, 1e-6);
  EXPECT_NEAR(map.lines[0].to_y_m, 2.0, 1e-6);
  EXPECT_GT(map.lines[0].covariance[0], 0.0);
  EXPECT_NE(map.lines[0].id, map.lines[1].id);
  const auto tracks = out.Get<slammtt_msgs::tracks_t>(out.messages.size() - 4);
  EXPECT_EQ(tracks.num_tracks, 0);  // a line is never a track
  const auto timing = out.Get<slammtt_msgs::stage_timing_t>(out.messages.size() - 1);
  EXPECT_EQ(timing.counter_value[5], 2);  // lines
  EXPECT_EQ(timing.counter_value[6], 2);  // line_updates
  EXPECT_EQ(timing.counter_value[7], 0);  // new_lines
}

TEST(EstimatorStageTest, BadMessagesAreCountedAndDroppedOnesReported) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  RecordingSink out;
  const std::vector<uint8_t> garbage = {1, 2, 3, 4, 5};
  Feed(&stage, "FEATURES", garbage, out);
  Feed(&stage, "ODOMETRY", garbage, out);
  std::vector<uint8_t> truncated = FeaturesBytes(5, {{5.0, 0.1}});
  truncated.resize(truncated.size() - 3);
  Feed(&stage, "FEATURES", truncated, out);
  EXPECT_TRUE(out.messages.empty());
  EXPECT_EQ(stage.counters().messages_undecodable, 3);
  // Out-of-order scan: only a status message, with the dropped message's utime.
  Feed(&stage, "FEATURES", FeaturesBytes(200000, {}), out);
  out.messages.clear();
  Feed(&stage, "FEATURES", FeaturesBytes(100000, {}), out);
  ASSERT_EQ(out.messages.size(), 1u);
  EXPECT_EQ(out.messages[0].channel, "ESTIMATOR_STATUS");
  const auto status = out.Get<slammtt_msgs::estimator_status_t>(0);
  EXPECT_EQ(status.utime, 100000);
  EXPECT_EQ(status.messages_out_of_order, 1);
  EXPECT_NE(status.last_event.find("dropped"), std::string::npos);
  EXPECT_EQ(status.messages_undecodable, 3);
  EXPECT_EQ(status.odometry_rejected, 0);
  EXPECT_EQ(status.updates_failed, 0);
  // A NaN odometry: a status message says so and counts it.
  out.messages.clear();
  Feed(&stage, "ODOMETRY", OdometryBytes(300000, std::nan(""), 0.0), out);
  ASSERT_EQ(out.messages.size(), 1u);
  const auto rejected = out.Get<slammtt_msgs::estimator_status_t>(0);
  EXPECT_NE(rejected.last_event.find("not finite"), std::string::npos);
  EXPECT_EQ(rejected.odometry_rejected, 1);
  EXPECT_EQ(rejected.messages_undecodable, 3);
  // Messages on other channels are ignored.
  out.messages.clear();
  Feed(&stage, "LASER_SCAN", garbage, out);
  EXPECT_TRUE(out.messages.empty());
}

TEST(EstimatorStageTest, SameMessagesSameBytes) {
  auto run = [] {
    EstimatorStageOptions options;
    options.seed = 3;
    EstimatorStage stage(options, Channels());
    RecordingSink out;
    for (int k = 0; k < 40; ++k) {
      const int64_t t = 125000 * k;
      const double walker = 0.1 * k;
      Feed(&stage, "ODOMETRY", OdometryBytes(t, 0.02 * k, 0.16), out);
      Feed(&stage, "FEATURES",
           FeaturesBytes(t, {{5.0, 0.3}, {6.0, -0.2}, {4.0 + walker, 0.5 - 0.05 * walker},
                             {4.3 + walker, 0.55 - 0.05 * walker}}),
           out);
    }
    std::vector<Published> deterministic;
    for (const Published& p : out.messages) {
      if (p.channel != "STAGE_TIMING") deterministic.push_back(p);
    }
    return deterministic;
  };
  const std::vector<Published> a = run();
  const std::vector<Published> b = run();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].channel, b[k].channel);
    EXPECT_EQ(a[k].bytes, b[k].bytes) << "message " << k;
  }
}

TEST(EstimatorStageTest, FactoryReadsTheStackConfiguration) {
  ProcessSettings settings;
  settings.config = Config::FromString("estimator:\n  mode: ransac_all_pairs\n", "stack.yaml");
  const std::unique_ptr<Stage> stage = CreateEstimatorStage(settings);
  EXPECT_EQ(stage->Name(), "estimator");
  EXPECT_EQ(static_cast<EstimatorStage*>(stage.get())->estimator().options().mode,
            AssociationMode::kRansacAllPairs);
}

}  // namespace
}  // namespace slammtt

namespace slammtt {
namespace {

// A LASER_GEOMETRY as slammtt-world publishes it for s2-lobby.
std::vector<uint8_t> LobbyGeometryBytes(int64_t utime) {
  slammtt_msgs::laser_geometry_t m{};
  m.utime = utime;
  m.mount_forward_m = 0.1;
  m.view_start_rad = -0.5 * (180.0 * M_PI / 180.0);
  m.view_end_rad = 0.5 * (180.0 * M_PI / 180.0);
  m.range_min_m = 0.1;
  m.range_max_m = 30.0;
  m.source = "slammtt-world, scenario s2-lobby";
  return Encode(m);
}

EstimatorStage StageOf(const std::string& yaml) {
  const Config config = Config::FromString(yaml, "stack.yaml");
  return EstimatorStage(ReadEstimatorOptions(config.Child("estimator")), Channels());
}

// The lines the stage writes to stderr while it handles `bytes` on LASER_GEOMETRY `times` times.
std::vector<std::string> GeometryLines(EstimatorStage* stage, const std::vector<uint8_t>& bytes,
                                       int times) {
  RecordingSink out;
  ::testing::internal::CaptureStderr();
  for (int k = 0; k < times; ++k) Feed(stage, "LASER_GEOMETRY", bytes, out);
  std::istringstream text(::testing::internal::GetCapturedStderr());
  EXPECT_TRUE(out.messages.empty());
  std::vector<std::string> lines;
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

TEST(EstimatorGeometryTest, ReadsWhichGeometryKeysTheConfigurationGives) {
  EXPECT_FALSE(ReadEstimatorOptions(Config()).geometry_given.any());
  const auto given = [](const std::string& key_value) {
    const Config c = Config::FromString("estimator:\n  " + key_value + "\n", "stack.yaml");
    return ReadEstimatorOptions(c.Child("estimator")).geometry_given;
  };
  const ConfiguredGeometryParts yaw = given("sensor_yaw_deg: 90");
  EXPECT_TRUE(yaw.mount && !yaw.field_of_view && !yaw.max_range);
  const ConfiguredGeometryParts view = given("field_of_view_start_deg: -120");
  EXPECT_TRUE(!view.mount && view.field_of_view && !view.max_range);
  const ConfiguredGeometryParts range = given("max_range_m: 12");
  EXPECT_TRUE(!range.mount && !range.field_of_view && range.max_range);
  EXPECT_FALSE(given("min_range_m: 0.1").any());  // the estimator's own gate, not geometry
}

TEST(EstimatorGeometryTest, WithoutTheKeysTakesTheLogsGeometryAndSaysSoOnce) {
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  const std::vector<std::string> lines = GeometryLines(&stage, LobbyGeometryBytes(0), 3);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("estimator: laser geometry the configuration does not give, taken from "
                          "LASER_GEOMETRY (slammtt-world, scenario s2-lobby): mount "
                          "forward 0.1 m, left 0 m, yaw 0 deg; field of view -90 to 90 deg; "
                          "max range 30 m"),
            std::string::npos)
      << lines[0];
  EXPECT_EQ(stage.estimator().options().sensor.forward_m, 0.1);
  EXPECT_EQ(stage.estimator().options().field_of_view_rad, 180.0 * M_PI / 180.0);
  EXPECT_EQ(stage.estimator().options().max_range_m, 30.0);
  EXPECT_EQ(stage.counters().geometry_messages, 3);
  EXPECT_EQ(stage.counters().geometry_disagreements, 0);
}

TEST(EstimatorGeometryTest, AnAgreeingConfigurationSaysNothing) {
  EstimatorStage stage = StageOf(
      "estimator:\n  sensor_forward_m: 0.1\n  sensor_left_m: 0.0\n"
      "  field_of_view_deg: 180\n  max_range_m: 30\n");
  EXPECT_TRUE(GeometryLines(&stage, LobbyGeometryBytes(0), 2).empty());
  EXPECT_EQ(stage.counters().geometry_disagreements, 0);
}

TEST(EstimatorGeometryTest, ADisagreeingConfigurationWarnsOnceInOneLineNamingBothValues) {
  // office's geometry on the lobby's log.
  EstimatorStage stage = StageOf(
      "estimator:\n  sensor_forward_m: 0.05\n  field_of_view_deg: 360\n  max_range_m: 12\n");
  const std::vector<std::string> lines = GeometryLines(&stage, LobbyGeometryBytes(0), 4);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("the configuration's laser geometry disagrees with LASER_GEOMETRY "
                          "(slammtt-world, scenario s2-lobby): mount: configuration (forward "
                          "0.05 m, left 0 m, yaw 0 deg), log (forward 0.1 m, left 0 m, yaw 0 "
                          "deg); field of view: configuration -180 to 180 deg, log -90 to 90 "
                          "deg; max range: configuration 12 m, log 30 m; the configuration's "
                          "is used"),
            std::string::npos)
      << lines[0];
  EXPECT_EQ(stage.counters().geometry_disagreements, 1);
  EXPECT_EQ(stage.estimator().options().sensor.forward_m, 0.05);
  EXPECT_EQ(stage.estimator().options().max_range_m, 12.0);
}

TEST(EstimatorGeometryTest, AnUnusableGeometryIsCountedWarnedOnceAndNotUsed) {
  slammtt_msgs::laser_geometry_t m{};
  m.mount_forward_m = std::nan("");
  m.view_start_rad = -1.0;
  m.view_end_rad = 1.0;
  m.range_max_m = 30.0;
  m.source = "two\nlines";  // stays one line
  EstimatorStage stage(EstimatorStageOptions{}, Channels());
  const std::vector<std::string> lines = GeometryLines(&stage, Encode(m), 3);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("(two?lines) not used: a value is not a finite number"),
            std::string::npos)
      << lines[0];
  EXPECT_EQ(stage.counters().geometry_rejected, 1);
  EXPECT_EQ(stage.estimator().options().sensor.forward_m, 0.0);
  const std::vector<uint8_t> garbage = {1, 2, 3};
  RecordingSink out;
  Feed(&stage, "LASER_GEOMETRY", garbage, out);
  EXPECT_EQ(stage.counters().messages_undecodable, 1);
}

}  // namespace
}  // namespace slammtt
