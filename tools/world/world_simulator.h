// The synthetic world, step by step: the robot drives its scenario motion, movers follow their
// paths, and the world produces, in time order, odometry readings and sensor frames (ground truth
// with per-object beam counts, a ray-cast laser scan and/or point features).
//
//   Scenario scenario = LoadScenario("config/scenarios/s1-crossing.yaml");   // or build in code
//   WorldSimulator world(scenario, /*seed=*/7, scenario.output);
//   while (!world.Done()) {
//     const WorldEvent event = world.Next();
//     if (event.kind == WorldEvent::Kind::kSensor) { ... event.sensor.scan ... }
//   }
//
// Time: integer microseconds since the scenario start. Odometry reading j is at
// round(j * 1e6 / odometry.rate_hz), sensor frame k at round(k * 1e6 / laser.rate_hz), both up to
// and including duration_s. At equal times the odometry reading comes first.
// Randomness: independent streams derived from the seed (odometry, laser noise, features, one per
// random-walk mover), so e.g. choosing scans instead of features does not change the odometry.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "tools/world/laser_model.h"
#include "tools/world/mover_path.h"
#include "tools/world/odometry_model.h"
#include "tools/world/person_gait.h"
#include "tools/world/point_features.h"
#include "tools/world/ray_caster.h"
#include "tools/world/robot_driver.h"
#include "tools/world/scenario.h"
#include "tools/world/static_geometry.h"

namespace slammtt {

// Ground truth of one compact object (a circle) or person at one moment (order: static circles
// in scenario order, then movers in scenario order, a person followed by its two legs).
struct ObjectTruth {
  int64_t id = 0;
  bool is_static = false;  // scenario class: static landmark or mover (even a standing mover)
  ObjectKind kind = ObjectKind::kPost;  // kFurniture, kPost, kDisc, kPerson or kLeg
  int64_t parent_id = -1;  // a leg: its person's id
  double x_m = 0.0;
  double y_m = 0.0;
  double vx_mps = 0.0;
  double vy_mps = 0.0;
  double radius_m = 0.0;    // a person: half the distance between its legs' outer sides
  int beams_on_object = 0;  // valid beams whose first hit is this object (a person: its legs)
  bool visible = false;     // a point feature was emitted (feature output), else beams >= 1
};

// Ground truth of one straight static surface (a wall, a side of a desk), in scenario order.
struct SegmentTruth {
  int64_t id = 0;  // the object it belongs to
  ObjectKind kind = ObjectKind::kWall;  // kWall or kFurniture
  Segment segment;
  int beams_on_segment = 0;  // valid beams whose first hit is this segment
};

struct RobotTruth {
  Pose2D pose;         // axle centre, world frame
  Pose2D sensor_pose;  // paper eq. 11
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

struct TruthSnapshot {
  int64_t time_us = 0;
  RobotTruth robot;
  std::vector<ObjectTruth> objects;  // every object that exists at time_us
  std::vector<SegmentTruth> segments;  // every static segment
};

// Everything the sensor produced at one scan time.
struct SensorFrame {
  int64_t time_us = 0;
  int64_t sequence = 0;  // 0, 1, 2, ...
  TruthSnapshot truth;
  bool has_scan = false;
  // Beams in measuring order (even lasers: LaserBeamAngles()); a beam's object is an index into
  // truth.objects, its segment an index into truth.segments.
  std::vector<SimulatedBeam> scan;
  bool has_features = false;
  // One per visible static circle, disc and person (not per leg; walls give none);
  // object = index in truth.objects.
  std::vector<PointFeature> features;
};

// The world at one moment for a robot driven from outside (drivers/sim_robot: the emulated
// base's motion): the truth without beam counts, the circles a laser can hit (statics, then
// discs and legs) and, per circle, the index of its object in truth.objects.
struct WorldScene {
  TruthSnapshot truth;
  std::vector<Circle> circles;
  std::vector<int> circle_object;
};

// Sets beams_on_object, visible (beams >= 1) and beams_on_segment of `truth` from measured
// beams whose `object` indexes truth.objects and `segment` truth.segments (a person counts the
// beams on its two legs, which follow it).
void CountBeamsIntoTruth(const std::vector<SimulatedBeam>& beams, TruthSnapshot* truth);

struct WorldEvent {
  enum class Kind { kOdometry, kSensor };
  Kind kind = Kind::kOdometry;
  int64_t time_us = 0;
  OdometryReading odometry;  // kind == kOdometry
  SensorFrame sensor;        // kind == kSensor
};

class WorldSimulator {
 public:
  // std::invalid_argument (one line per problem, joined by "; ") when FindScenarioProblems()
  // finds any.
  WorldSimulator(const Scenario& scenario, uint64_t seed, SensorOutput output);

  // True when every event up to duration_s has been returned.
  bool Done() const;
  // Time of the event Next() will return (meaningless when Done()).
  int64_t NextEventTimeUs() const;
  // The next event in time order. std::logic_error when Done().
  WorldEvent Next();

  // Replaces the scenario's robot motion by this command from now on (live mode following
  // VELOCITY_COMMAND); nullopt returns to the scenario motion. Linear speed is clamped to
  // +-kMaxRobotSpeedMps. Takes effect at the next control tick.
  void SetCommandOverride(const std::optional<VelocityCommand>& command);

  // The scene at time_us with the robot at `robot` (live robots driven from outside; call with
  // non-decreasing times, as the people's gait moves on). Draws nothing.
  WorldScene SceneAt(int64_t time_us, const RobotTruth& robot);
  // The static segments in truth.segments order, and per segment / per static circle the
  // probability that it gives the laser no return (scenario dropout_probability).
  const std::vector<Segment>& segments() const { return segments_; }
  const ArtefactInputs& surface_dropouts() const { return artefact_inputs_; }

  const Scenario& scenario() const { return scenario_; }
  int64_t duration_us() const { return duration_us_; }
  // The even beam layout (a sampled laser's scans carry their own angles).
  const std::vector<double>& beam_angles_rad() const { return beam_angles_rad_; }
  const StaticGeometry& static_geometry() const { return static_geometry_; }
  // Ground truth of the robot at the last event's time.
  const RobotTruth& robot() const { return robot_; }

 private:
  void AdvanceRobotTo(int64_t time_us);
  // The truth at time_us (moving the movers' legs there), the circles the laser can hit and,
  // for each circle, the index of its object in the truth.
  TruthSnapshot TruthAt(int64_t time_us, std::vector<Circle>* circles,
                        std::vector<int>* circle_object);
  std::vector<FeatureTarget> FeatureTargets(const TruthSnapshot& truth,
                                            const std::vector<int>& circle_object) const;
  SensorFrame MakeSensorFrame(int64_t time_us);

  Scenario scenario_;
  SensorOutput output_;
  int64_t duration_us_ = 0;
  std::vector<double> beam_angles_rad_;
  std::vector<MoverPath> mover_paths_;
  std::vector<std::optional<PersonGait>> gaits_;  // per mover: its legs, or none for a disc
  StaticGeometry static_geometry_;
  std::vector<Segment> segments_;
  ArtefactInputs artefact_inputs_;  // dropout probabilities (per circle: statics, then zeros)
  BeamAngleSequence beam_sequence_;
  RobotDriver driver_;
  std::optional<VelocityCommand> command_override_;

  std::mt19937_64 odometry_rng_;
  std::mt19937_64 laser_rng_;
  std::mt19937_64 feature_rng_;
  std::mt19937_64 artefact_rng_;
  std::mt19937_64 beam_angle_rng_;

  // Robot state: pose at robot_time_us_, command held since the last control tick.
  int64_t robot_time_us_ = 0;
  int64_t next_control_us_ = 0;
  VelocityCommand command_;
  RobotTruth robot_;
  double distance_since_odometry_m_ = 0.0;
  double rotation_since_odometry_rad_ = 0.0;

  OdometryIntegrator odometry_;
  int64_t next_odometry_index_ = 0;
  int64_t next_scan_index_ = 0;
};

}  // namespace slammtt
