// Landmarks scattered along the robot's path (tools/world/scattered_landmarks.h): where they
// stand, that the seed draws the layout, the loader's section and its bad values, and the
// simulator's ground truth with them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "runtime/config.h"
#include "tools/world/scattered_landmarks.h"
#include "tools/world/scenario_loader.h"
#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

// A 100 x 40 m rectangle, driven round (closed).
std::vector<PlanarPoint> Rectangle() { return {{0, 0}, {100, 0}, {100, 40}, {0, 40}}; }

double DistanceToSegment(const PlanarPoint& p, const PlanarPoint& a, const PlanarPoint& b) {
  const double dx = b.x_m - a.x_m;
  const double dy = b.y_m - a.y_m;
  double t = ((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / (dx * dx + dy * dy);
  t = std::min(1.0, std::max(0.0, t));
  return std::hypot(p.x_m - a.x_m - t * dx, p.y_m - a.y_m - t * dy);
}

double DistanceToClosedPath(const PlanarPoint& p, const std::vector<PlanarPoint>& path) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < path.size(); ++i) {
    best = std::min(best, DistanceToSegment(p, path[i], path[(i + 1) % path.size()]));
  }
  return best;
}

TEST(ScatteredLandmarksTest, StandWithinTheirBandApartAndNumberedInOrder) {
  ScatteredLandmarksSpec spec;
  spec.count = 500;
  spec.first_id = 1000;
  std::mt19937_64 rng(3);
  const std::vector<StaticObjectSpec> landmarks = ScatterLandmarks(spec, Rectangle(), true, rng);
  ASSERT_EQ(landmarks.size(), 500u);
  int inside = 0;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const StaticObjectSpec& l = landmarks[i];
    EXPECT_EQ(l.id, 1000 + static_cast<int64_t>(i));
    EXPECT_EQ(l.shape, StaticShape::kCircle);
    EXPECT_EQ(l.kind, ObjectKind::kPost);
    EXPECT_DOUBLE_EQ(l.radius_m, 0.2);
    const double d = DistanceToClosedPath({l.x_m, l.y_m}, Rectangle());
    EXPECT_GE(d, spec.min_offset_m - 1e-9) << i;
    EXPECT_LE(d, spec.max_offset_m + 1e-9) << i;
    for (size_t j = 0; j < i; ++j) {
      EXPECT_GE(std::hypot(l.x_m - landmarks[j].x_m, l.y_m - landmarks[j].y_m), 1.0 - 1e-9);
    }
    inside += (l.x_m > 0 && l.x_m < 100 && l.y_m > 0 && l.y_m < 40) ? 1 : 0;
  }
  // Both sides of the path: inside the loop and outside it (the outer band is larger).
  EXPECT_GT(inside, 150);
  EXPECT_LT(inside, 250);
}

TEST(ScatteredLandmarksTest, AnOpenPathHasNoClosingSide) {
  ScatteredLandmarksSpec spec;
  spec.count = 300;
  std::mt19937_64 rng(5);
  const std::vector<PlanarPoint> path = {{0, 0}, {100, 0}};
  for (const StaticObjectSpec& l : ScatterLandmarks(spec, path, false, rng)) {
    EXPECT_GE(std::abs(l.y_m), 2.0 - 1e-9);
    EXPECT_LE(std::abs(l.y_m), 12.0 + 1e-9);
    EXPECT_GE(l.x_m, -12.0);
    EXPECT_LE(l.x_m, 112.0);
  }
}

Scenario LoopScenario(int count) {
  Scenario s;
  s.duration_s = 1.0;
  s.output = SensorOutput::kFeatures;
  s.robot.waypoints = Rectangle();
  s.robot.loop = true;
  s.robot.start = Pose2D{0.0, 0.0, 0.0};
  s.scattered_landmarks.count = count;
  return s;
}

TEST(ScatteredLandmarksTest, TheSeedDrawsTheLayout) {
  const Scenario a = WithScatteredLandmarks(LoopScenario(50), 1);
  const Scenario b = WithScatteredLandmarks(LoopScenario(50), 1);
  const Scenario c = WithScatteredLandmarks(LoopScenario(50), 2);
  ASSERT_EQ(a.statics.size(), 50u);
  EXPECT_EQ(a.scattered_landmarks.count, 0);
  int same = 0;
  for (size_t i = 0; i < a.statics.size(); ++i) {
    EXPECT_EQ(a.statics[i].x_m, b.statics[i].x_m);
    EXPECT_EQ(a.statics[i].y_m, b.statics[i].y_m);
    same += a.statics[i].x_m == c.statics[i].x_m ? 1 : 0;
  }
  EXPECT_EQ(same, 0);
}

TEST(ScatteredLandmarksTest, TooLittleRoomIsRefusedWithTheNumbers) {
  Scenario s = LoopScenario(5000);
  s.scattered_landmarks.min_spacing_m = 5.0;
  try {
    WithScatteredLandmarks(s, 1);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scattered_landmarks: room for "), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(" of 5000 landmarks"), std::string::npos) << e.what();
  }
}

TEST(ScatteredLandmarksTest, TheSimulatorsGroundTruthHoldsThem) {
  Scenario s = LoopScenario(200);
  StaticObjectSpec post;
  post.id = 7;
  post.x_m = 50;
  post.y_m = 20;
  s.statics.push_back(post);
  WorldSimulator world(s, 4, SensorOutput::kFeatures);
  EXPECT_EQ(world.scenario().statics.size(), 201u);
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    std::set<int64_t> ids;
    for (const ObjectTruth& o : e.sensor.truth.objects) {
      EXPECT_TRUE(o.is_static);
      ids.insert(o.id);
    }
    EXPECT_EQ(ids.size(), 201u);
    EXPECT_EQ(ids.count(7), 1u);
    EXPECT_EQ(ids.count(1), 0u);  // the post's id is 7, the scattered ones 8...
    EXPECT_EQ(ids.count(8), 1u);
    EXPECT_EQ(ids.count(207), 1u);
    EXPECT_FALSE(e.sensor.features.empty());
    break;
  }
}

std::string LoadError(const std::string& yaml) {
  try {
    LoadScenarioFromString(yaml, "loop.yaml", ".");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kLoopYaml = R"(duration_s: 5
robot:
  speed_mps: 1
  loop: true
  waypoints: [[0, 0], [100, 0], [100, 40], [0, 40]]
)";

TEST(ScatteredLandmarksTest, TheLoaderReadsTheSectionAndRefusesBadValues) {
  const Scenario s = LoadScenarioFromString(std::string(kLoopYaml) + R"(scattered_landmarks:
  count: 30
  min_offset_m: 3
  max_offset_m: 9
  min_spacing_m: 2
  radius_m: 0.3
  first_id: 500
)", "loop.yaml", ".");
  EXPECT_EQ(s.scattered_landmarks.count, 30);
  EXPECT_DOUBLE_EQ(s.scattered_landmarks.min_offset_m, 3);
  EXPECT_DOUBLE_EQ(s.scattered_landmarks.max_offset_m, 9);
  EXPECT_DOUBLE_EQ(s.scattered_landmarks.min_spacing_m, 2);
  EXPECT_DOUBLE_EQ(s.scattered_landmarks.radius_m, 0.3);
  EXPECT_EQ(s.scattered_landmarks.first_id, 500);
  EXPECT_TRUE(s.statics.empty());  // drawn by the simulator, from its seed

  const std::string loop = kLoopYaml;
  EXPECT_EQ(LoadError(loop + "scattered_landmarks: {count: -1}\n"),
            "loop.yaml:6: scattered_landmarks.count: must be in [0, 100000], got -1");
  EXPECT_EQ(LoadError(loop + "scattered_landmarks: {count: 5, min_offset_m: 12}\n"),
            "loop.yaml:6: scattered_landmarks.min_offset_m: must be within (0, max_offset_m), "
            "got 12");
  EXPECT_EQ(LoadError(loop + "scattered_landmarks: {count: 5, colour: red}\n"),
            "loop.yaml:6: scattered_landmarks.colour: unknown key");
  EXPECT_NE(LoadError(loop + "statics: [{id: 3, x_m: 1, y_m: 1}]\n"
                             "scattered_landmarks: {count: 5, first_id: 1}\n")
                .find("scattered_landmarks.first_id: ids 1..5 overlap statics[0]'s id 3"),
            std::string::npos);
  EXPECT_NE(LoadError("duration_s: 5\nscattered_landmarks: {count: 5}\n")
                .find("scattered_landmarks: needs a robot path of at least two waypoints"),
            std::string::npos);
}

}  // namespace
}  // namespace slammtt
