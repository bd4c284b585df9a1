// The synthetic world as data: robot motion, static and moving objects, laser, odometry and
// point-feature settings of one scenario. A Scenario is built in code (tests) or loaded from a
// YAML file by tools/world/scenario_loader.h; docs/world.md lists every key with its units and
// default. Nothing here reads files or clocks.
//
// Static objects are circles (posts, pillars, chair and table legs), polygons and polylines
// (walls of rooms and corridors with door openings, desks, cabinets, boxes), each with a kind
// (wall, furniture, post). Movers are discs (the paper's objects: it treats detected objects as
// points, section 2) or people on two legs driven by a walking gait (person_gait.h).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "tools/world/planar_pose.h"

namespace slammtt {

// The robot may not be faster than the paper's simulated robot ("up to 2 m/s", section 5.1).
inline constexpr double kMaxRobotSpeedMps = 2.0;
// Every coordinate of a scenario lies within +-kMaxCoordinateM (values beyond are rejected).
inline constexpr double kMaxCoordinateM = 1e6;
// Durations and times of a scenario are at most this long (11.6 days).
inline constexpr double kMaxScenarioDurationS = 1e6;

// Which sensor messages the world produces.
enum class SensorOutput {
  kFeatures,  // point features straight from the visible objects (the paper's simulation)
  kScans,     // raw ray-cast laser scans (input of the segmenter)
  kBoth,
};
// "features", "scans", "both"; false for anything else.
bool ParseSensorOutput(const std::string& text, SensorOutput* output);
const char* SensorOutputName(SensorOutput output);

// Effects of real scanners that the ideal ray caster lacks (laser_model.h; all off by default so
// that a scenario without them gives exactly the scans it gave before they existed).
struct LaserArtefactSpec {
  // Mixed pixels at depth edges: a beam's footprint is beam_divergence_deg wide; when its two
  // edges meet different surfaces more than mixed_pixel_min_gap_m apart in range, the beam
  // straddles a depth edge and, with probability mixed_pixel_probability, returns a range drawn
  // uniformly between the two surfaces' ranges.
  double mixed_pixel_probability = 0.0;  // [0, 1]
  double beam_divergence_deg = 0.18;     // (0, 10]
  double mixed_pixel_min_gap_m = 0.05;   // > 0
  // No return when the angle between the beam and the surface normal exceeds this (90: never).
  double grazing_dropout_deg = 90.0;     // (0, 90]
  // Range noise that grows with range: sigma = range_noise_m + range_noise_per_m * range.
  double range_noise_per_m = 0.0;        // >= 0
  // RPLIDAR-like beam angles: samples at sample_rate_hz while the head turns at about rate_hz,
  // the turn rate of each revolution scaled by 1 + N(0, rotation_jitter^2), each sample's angle
  // off by N(0, angle_jitter_deg^2); a revolution starts where the previous one ended, so the
  // first angle and the number of beams change from scan to scan. 0 (off): even beams of
  // resolution_deg.
  double sample_rate_hz = 0.0;           // 0 or [10, 1e6]
  double rotation_jitter = 0.0;          // [0, 0.2]
  double angle_jitter_deg = 0.0;         // [0, 5]
};

// A 2D laser scanner. Beam i points at angle -fov/2 + i * resolution in the sensor frame; a
// 360-degree sensor has round(360 / resolution) beams starting at -180 degrees (no beam twice),
// a narrower one floor(fov / resolution) + 1 beams covering both edges. A scan is instantaneous:
// every beam sees the world at the scan's time (scan_duration_us = 0).
// Defaults: the robot's RPLIDAR A2 at 10 Hz (about 0.9 degree, 400 beams per revolution, range
// 0.15-12 m; paper section 5.2 and the A2 datasheet).
struct LaserSpec {
  double fov_deg = 360.0;         // (0, 360]
  double resolution_deg = 0.9;    // angle between neighbouring beams, > 0
  double min_range_m = 0.15;      // nearer returns are invalid
  double max_range_m = 12.0;      // farther surfaces give no return
  double rate_hz = 10.0;          // scans per second
  double range_noise_m = 0.01;    // standard deviation of the Gaussian noise of each beam
  double mount_a_m = 0.0;         // sensor position on the robot, paper eq. 11: forward
  double mount_b_m = 0.0;         //   and left of the axle centre
  double mount_yaw_deg = 0.0;     // the laser's heading, CCW from the robot's, [-180, 180]
  LaserArtefactSpec artefacts;    // all off by default
};

// Point features emitted straight from the objects (paper section 5.1: range/bearing noise 0.2 m
// and 2 degrees). The field of view, ranges, rate and mount are the laser's.
struct FeatureSpec {
  double range_noise_m = 0.2;
  double bearing_noise_deg = 2.0;
  double detection_probability = 1.0;  // a visible object yields a feature with this probability
};

// Wheel odometry of a differential-drive base, paper eq. 1. Each reading measures the rotation
// of both wheels since the previous reading:
//   measured = true * (1 + slip_bias + slip_std * n1) + encoder_noise_rad * n2  (n1, n2 ~ N(0,1))
// where the additive encoder noise applies only to a wheel that turned (a wheel standing still
// reads no motion). The base integrates the measured increments with eq. 1 from (0, 0, 0).
// Defaults: P3-DX wheels of 195 mm diameter, about 0.33 m apart; noise-free.
struct OdometrySpec {
  double rate_hz = 20.0;
  double wheel_radius_m = 0.0975;  // r of eq. 1
  double axle_length_m = 0.33;     // D of eq. 1: distance between the wheels
  double encoder_noise_rad = 0.0;  // additive standard deviation per reading and wheel
  double slip_std = 0.0;           // relative standard deviation per reading and wheel
  double left_slip_bias = 0.0;     // systematic relative error of the left wheel
  double right_slip_bias = 0.0;    // and of the right wheel
};

// One constant-velocity piece of the robot's velocity profile.
struct VelocitySegment {
  double duration_s = 0.0;
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

struct PlanarPoint {
  double x_m = 0.0;
  double y_m = 0.0;
};

// How the robot moves: a velocity profile (used when `waypoints` is empty) or waypoints followed
// by a deterministic controller (turn towards the next waypoint at yaw rate
// clamp(turn_gain * heading error, +-max_angular), drive at speed * max(0, cos(heading error)),
// switch to the next waypoint within waypoint_tolerance). Commands change every control period
// (10 ms); in between the robot moves exactly on arcs (MoveUnicycle). After the last profile
// segment or waypoint the robot stops, unless `loop` starts the list again.
struct RobotMotionSpec {
  Pose2D start;                          // world pose at time 0
  std::vector<VelocitySegment> profile;  // |linear_mps| <= kMaxRobotSpeedMps
  std::vector<PlanarPoint> waypoints;
  double speed_mps = 0.5;                // waypoint mode, (0, kMaxRobotSpeedMps]
  double max_angular_radps = 1.0;        // waypoint mode
  double turn_gain_per_s = 2.0;          // waypoint mode
  double waypoint_tolerance_m = 0.2;     // waypoint mode
  bool loop = false;
};

// What an object is (ground truth kind; the LCM message constants are mapped in
// world_messages.cc). Statics are walls, furniture or posts; movers discs or people; a person's
// legs are objects of their own.
enum class ObjectKind { kWall, kFurniture, kPost, kDisc, kPerson, kLeg };
const char* ObjectKindName(ObjectKind kind);

// The shape of a static object.
enum class StaticShape {
  kCircle,    // centre x_m, y_m and radius_m: a post, a pillar, one leg
  kPolygon,   // closed: vertices, side k from vertex k to vertex k + 1 (the last to the first)
  kPolyline,  // open: sides between consecutive vertices
  kBox,       // rectangle: centre x_m, y_m, size_x_m by size_y_m turned by heading_rad
  kLegs,      // four circles of leg_radius_m at the corners of a box (a chair or a table)
};

// A gap in one side of a polygon or polyline (a door): from offset_m to offset_m + width_m
// measured along side `side` from its first vertex.
struct WallOpening {
  int side = 0;
  double offset_m = 0.0;
  double width_m = 0.0;
};

struct StaticObjectSpec {
  int64_t id = 0;  // kLegs: the four legs are ids id .. id + 3
  double x_m = 0.0;  // kCircle, kBox, kLegs: centre
  double y_m = 0.0;
  double radius_m = 0.2;            // kCircle
  ObjectKind kind = ObjectKind::kPost;  // kWall, kFurniture or kPost
  StaticShape shape = StaticShape::kCircle;
  std::vector<PlanarPoint> vertices;  // kPolygon, kPolyline
  std::vector<WallOpening> openings;  // kPolygon, kPolyline
  double size_x_m = 1.0;            // kBox, kLegs: extent along the heading
  double size_y_m = 1.0;            //   and across it
  double heading_rad = 0.0;         // kBox, kLegs
  double leg_radius_m = 0.02;       // kLegs
  // Share of beams that hit the object and get no return (glass, black surfaces), [0, 1].
  double dropout_probability = 0.0;
};
// Number of object ids a static uses (4 for kLegs, else 1).
int StaticIdCount(const StaticObjectSpec& spec);

// A point of a recorded or scripted trajectory.
struct TimedPoint {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
};

// A waypoint of a mover; the mover stands still wait_s seconds on arrival.
struct MoverWaypoint {
  double x_m = 0.0;
  double y_m = 0.0;
  double wait_s = 0.0;
};

enum class MoverKind {
  kConstantVelocity,  // from `start` at appear_s with (vx, vy): paper eqs. 6-7
  kWaypoints,         // along `waypoints` at speed_mps
  kTrajectory,        // through `trajectory` points, linearly interpolated (recorded paths)
  kRandomWalk,        // straight legs at speed_mps with random turns, inside `area`
};
// What a waypoint mover does after its last waypoint.
enum class PathEnd { kStay, kLeave, kLoop };
// What the laser sees of a mover: one disc of radius_m, or a person's two legs (person_gait.h).
enum class MoverBody { kDisc, kLegs };
// "discs"/"disc", "legs"; false for anything else.
bool ParseMoverBody(const std::string& text, MoverBody* body);

// A legged person: two legs of radius_m whose centres stand hip_width_m apart across the
// heading (issue 11: radius about 0.05-0.07 m, hip width about 0.2 m); gait in person_gait.h.
// A leg's id is 10 * person id + 1 (left) or + 2 (right).
struct LegSpec {
  double radius_m = 0.06;      // [0.001, 0.5]
  double hip_width_m = 0.2;    // [0, 2]
  double sway_m = 0.01;        // standing sway amplitude, [0, 0.2]
};
int64_t LegId(int64_t person_id, int leg);

// Random walk: legs of exponentially distributed duration (mean mean_leg_s, at least 0.5 s);
// at the start of each leg the heading turns by a uniform angle in [-max_turn, +max_turn] or,
// with probability reverse_probability, by exactly 180 degrees. A leg that would leave `area`
// heads instead for a uniformly drawn point inside it. The path is drawn once, at the start,
// from the object's own random stream (DeriveSeed(seed, id)): the same seed gives the same walk.
struct RandomWalkSpec {
  double heading_rad = 0.0;  // initial heading
  double mean_leg_s = 4.0;
  double max_turn_rad = 1.5707963267948966;
  double reverse_probability = 0.0;
  double area_min_x_m = -10.0;
  double area_min_y_m = -10.0;
  double area_max_x_m = 10.0;
  double area_max_y_m = 10.0;
};

// A moving object. It exists from appear_s (inclusive) to disappear_s (exclusive), further limited
// by its path: a trajectory exists only between its first and last point, a waypoint path with
// at_end = kLeave until it reaches its last waypoint. While it exists and its path does not say
// where it is (before the first point), it stands at the first point. It is a mover (ground-truth
// class MOVING) even while it stands still.
struct MoverSpec {
  int64_t id = 0;
  double radius_m = 0.25;
  MoverKind kind = MoverKind::kConstantVelocity;
  double appear_s = 0.0;
  double disappear_s = std::numeric_limits<double>::infinity();
  // kConstantVelocity and kRandomWalk: position at appear_s.
  double start_x_m = 0.0;
  double start_y_m = 0.0;
  // kConstantVelocity.
  double vx_mps = 0.0;
  double vy_mps = 0.0;
  // kWaypoints (starting at the first waypoint at appear_s) and kRandomWalk.
  double speed_mps = 1.0;
  std::vector<MoverWaypoint> waypoints;
  PathEnd at_end = PathEnd::kStay;
  // kTrajectory: strictly increasing t_s.
  std::vector<TimedPoint> trajectory;
  // kRandomWalk.
  RandomWalkSpec random_walk;
  // Disc or legs; nullopt: the scenario's `people`.
  std::optional<MoverBody> body;
};

// Point landmarks (posts) scattered along the robot's waypoint path, so that a long route can
// carry thousands of landmarks without listing them (the large-loop family, issue 14). Each
// landmark lies at a point of the path drawn uniformly by arc length (the closed polygon
// through the waypoints when the robot loops, else the open polyline), offset across the path
// to a side drawn at random by a distance uniform in [min_offset_m, max_offset_m]; a draw
// nearer than min_offset_m to any part of the path (inside a corner) or nearer than
// min_spacing_m to a landmark already placed is drawn again. The layout comes from the run's
// seed (scattered_landmarks.h), so every seed is another world of the same family. Ids
// first_id, first_id + 1, ... in placement order (first_id 0: one past the statics' largest
// id, 1 without statics); kind post.
struct ScatteredLandmarksSpec {
  int count = 0;               // [0, 100000]; 0: none
  double min_offset_m = 2.0;   // (0, max_offset_m)
  double max_offset_m = 12.0;  // <= 1000
  double min_spacing_m = 1.0;  // [0, 100]
  double radius_m = 0.2;       // (0, 10]
  int64_t first_id = 0;
};

struct Scenario {
  std::string name;
  double duration_s = 60.0;
  // utime of simulated time 0 in logs, so that logs are byte-identical (a fixed epoch,
  // 2023-11-14T22:13:20Z by default); live runs replace it with the wall clock at start.
  int64_t start_utime = 1700000000000000;
  SensorOutput output = SensorOutput::kScans;
  LaserSpec laser;
  FeatureSpec features;
  OdometrySpec odometry;
  RobotMotionSpec robot;
  std::vector<StaticObjectSpec> statics;
  ScatteredLandmarksSpec scattered_landmarks;  // added to statics by the simulator
  std::vector<MoverSpec> movers;
  MoverBody people = MoverBody::kDisc;  // body of movers that do not choose one
  LegSpec legs;
};

// The body a mover has in this scenario.
MoverBody BodyOf(const Scenario& scenario, const MoverSpec& mover);

// Every problem of a scenario built in code, one line each ("movers[2].radius_m: must be
// positive, got -1"); empty when the scenario can be simulated. Besides signs and orders it
// bounds magnitudes so that nothing overflows: durations and times up to 1e6 s, coordinates
// within +-kMaxCoordinateM, mover speeds up to 50 m/s, radii up to 1000 m, at most 100000
// static objects and 100000 vertices or openings per polygon (every beam is tested against every
// circle and segment), person ids within +-1e17 (leg ids 10 * id + 1, + 2). The YAML loader
// reports the same problems with file and line; WorldSimulator refuses a scenario with any.
std::vector<std::string> FindScenarioProblems(const Scenario& scenario);

}  // namespace slammtt
