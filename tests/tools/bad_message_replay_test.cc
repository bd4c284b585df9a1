// One bad message in a real pipeline run (issue 15, item 2): s2-lobby seed 1 (30 s of raw
// scans through the segmenter and the estimator) replayed clean and with one changed message:
// an ODOMETRY at x = 1e300, an ODOMETRY at utime -1, a LASER_SCAN (hence its FEATURES) 1e12 us
// ahead. Scored by slammtt-eval --json. Each run must publish no non-finite POSE, MAP or TRACKS
// value, restart nothing, and keep its ATE within 0.02 m of the clean run's. Prints the figures.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

struct Scored {
  double ate_m = 0.0;
  int poses = 0;
  int non_finite = 0;  // POSE, MAP or TRACKS messages with a non-finite value
  slammtt_msgs::estimator_status_t status{};
};

template <class Msg>
Msg DecodeOrFail(const LogEvent& e) {
  Msg m;
  EXPECT_TRUE(Decode(e.data.data(), static_cast<int>(e.data.size()), &m)) << e.channel;
  return m;
}

bool Finite(const slammtt_msgs::pose_t& p) {
  bool ok = std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.heading_rad);
  for (double c : p.covariance) ok = ok && std::isfinite(c);
  return ok;
}

bool Finite(const slammtt_msgs::tracks_t& t) {
  for (const auto& track : t.tracks) {
    if (!std::isfinite(track.x_m) || !std::isfinite(track.y_m) || !std::isfinite(track.vx_mps) ||
        !std::isfinite(track.vy_mps)) {
      return false;
    }
    for (double c : track.covariance) {
      if (!std::isfinite(c)) return false;
    }
  }
  return true;
}

bool Finite(const slammtt_msgs::map_t& m) {
  for (const auto& l : m.landmarks) {
    if (!std::isfinite(l.x_m) || !std::isfinite(l.y_m)) return false;
    for (double c : l.covariance) {
      if (!std::isfinite(c)) return false;
    }
  }
  return true;
}

class BadMessageReplayTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    directory_ = new testing::TempDir("slammtt-bad-message");
    ASSERT_EQ(testing::Shell(Bin("slammtt-world") + " --scenario s2-lobby --seed 1 --duration 30 " +
                             "--log " + directory_->File("world.lcm") + " > /dev/null 2>&1"),
              0);
    world_ = new std::vector<LogEvent>(testing::ReadLog(directory_->File("world.lcm")));
    clean_ = new Scored(Run("clean", *world_));
  }
  static void TearDownTestSuite() {
    delete clean_;
    delete world_;
    delete directory_;
  }

  static Scored Run(const std::string& name, const std::vector<LogEvent>& events) {
    const std::string in = directory_->File(name + ".lcm");
    const std::string out = directory_->File(name + ".out.lcm");
    const std::string json = directory_->File(name + ".json");
    testing::WriteLog(in, events);
    const std::string config = std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/s2-lobby.yaml";
    std::string output;
    EXPECT_EQ(testing::Shell(Bin("slammtt-replay") + " --quiet --no-timing " + in + " -o " + out +
                                 " --config " + config + " --stage segmenter --stage estimator",
                             &output),
              0)
        << output;
    EXPECT_EQ(testing::Shell(Bin("slammtt-eval") + " --quiet " + out + " --json " + json +
                                 " > /dev/null", &output),
              0)
        << output;
    Scored scored;
    std::ifstream report(json);
    const nlohmann::json r = nlohmann::json::parse(report);
    scored.ate_m = r["ate_rmse_m"].is_number() ? r["ate_rmse_m"].get<double>() : 1e9;
    for (const LogEvent& e : testing::ReadLog(out)) {
      if (e.channel == "POSE") {
        ++scored.poses;
        scored.non_finite += Finite(DecodeOrFail<slammtt_msgs::pose_t>(e)) ? 0 : 1;
      } else if (e.channel == "TRACKS") {
        scored.non_finite += Finite(DecodeOrFail<slammtt_msgs::tracks_t>(e)) ? 0 : 1;
      } else if (e.channel == "MAP") {
        scored.non_finite += Finite(DecodeOrFail<slammtt_msgs::map_t>(e)) ? 0 : 1;
      } else if (e.channel == "ESTIMATOR_STATUS") {
        scored.status = DecodeOrFail<slammtt_msgs::estimator_status_t>(e);
      }
    }
    return scored;
  }

  // The world log with its `nth` message of `channel` changed by `change`.
  template <class Msg>
  static std::vector<LogEvent> WithOne(const std::string& channel, int nth,
                                       const std::function<void(Msg*)>& change) {
    std::vector<LogEvent> events = *world_;
    int seen = 0;
    for (LogEvent& e : events) {
      if (e.channel != channel || seen++ != nth) continue;
      Msg m = DecodeOrFail<Msg>(e);
      change(&m);
      e.data = Encode(m);
      break;
    }
    return events;
  }

  static void ExpectHarmless(const std::string& name, const Scored& faulty) {
    std::printf("s2-lobby seed 1, %s: ATE clean %.4f m, now %.4f m; POSE %d / %d; non-finite "
                "POSE/MAP/TRACKS %d; restarts %lld; odometry_rejected %lld; "
                "time_jumps_rejected %lld\n",
                name.c_str(), clean_->ate_m, faulty.ate_m, faulty.poses, clean_->poses,
                faulty.non_finite, static_cast<long long>(faulty.status.restarts),
                static_cast<long long>(faulty.status.odometry_rejected),
                static_cast<long long>(faulty.status.time_jumps_rejected));
    EXPECT_EQ(faulty.non_finite, 0);
    EXPECT_EQ(faulty.status.restarts, 0);
    EXPECT_GE(faulty.poses, clean_->poses - 1);
    EXPECT_LE(faulty.ate_m, clean_->ate_m + 0.02);
  }

  static testing::TempDir* directory_;
  static std::vector<LogEvent>* world_;
  static Scored* clean_;
};

testing::TempDir* BadMessageReplayTest::directory_ = nullptr;
std::vector<LogEvent>* BadMessageReplayTest::world_ = nullptr;
Scored* BadMessageReplayTest::clean_ = nullptr;

TEST_F(BadMessageReplayTest, TheCleanRunIsFinite) {
  std::printf("s2-lobby seed 1, clean: ATE %.4f m, POSE %d\n", clean_->ate_m, clean_->poses);
  EXPECT_EQ(clean_->non_finite, 0);
  EXPECT_GT(clean_->poses, 200);
}

TEST_F(BadMessageReplayTest, OneOdometryAtXOf1e300) {
  const Scored faulty = Run("x1e300", WithOne<slammtt_msgs::odometry_t>(
                                          "ODOMETRY", 100, [](auto* m) { m->x_m = 1e300; }));
  ExpectHarmless("ODOMETRY x = 1e300", faulty);
  EXPECT_EQ(faulty.status.odometry_rejected, 1);
}

TEST_F(BadMessageReplayTest, OneOdometryAtUtimeMinusOne) {
  const Scored faulty = Run("utime-1", WithOne<slammtt_msgs::odometry_t>(
                                           "ODOMETRY", 100, [](auto* m) { m->utime = -1; }));
  ExpectHarmless("ODOMETRY utime -1", faulty);
  EXPECT_EQ(faulty.status.time_jumps_rejected, 1);
}

TEST_F(BadMessageReplayTest, OneScanFarAhead) {
  const Scored faulty =
      Run("ahead", WithOne<slammtt_msgs::laser_scan_t>(
                       "LASER_SCAN", 100, [](auto* m) { m->utime += 1000000000000; }));
  ExpectHarmless("LASER_SCAN (FEATURES) +1e12 us", faulty);
  EXPECT_EQ(faulty.status.time_jumps_rejected, 1);
}

}  // namespace
}  // namespace slammtt
