// What a scenario offers an estimator, measured on a run of the simulator: how long each mover
// is in view and visible, how often and how long it is occluded, how many static landmarks are
// visible per scan, and the closest approaches (surface gaps) between objects and to the robot.
// Used to design fair scenarios (docs/world.md quotes the figures of the shipped ones) and by the
// tests that keep them so; `slammtt-world --report` prints it.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tools/world/world_simulator.h"

namespace slammtt {

struct MoverReport {
  int64_t id = 0;
  double exists_s = 0.0;    // scan periods in which it existed
  double in_view_s = 0.0;   // ... with its centre inside the field of view and range
  double visible_s = 0.0;   // ... and visible (truth `visible`)
  int occlusions = 0;       // episodes in view but not visible
  double longest_occlusion_s = 0.0;
  double longest_visible_s = 0.0;  // longest run of consecutive visible scans
};

// A time in which a mover was in view but not visible.
struct OcclusionEpisode {
  int64_t id = 0;
  int64_t occluder_id = 0;  // first object on the line of sight at the start; -1 if none
  bool occluder_is_static = false;
  double start_s = 0.0;     // first scan without visibility
  double end_s = 0.0;       // last scan without visibility
};

// A closest approach between two things at one scan time.
struct ClosestApproach {
  // Surface gap: centre distance minus radii, or distance from a centre to a wall segment
  // minus the radius (negative: overlap). A legged person's surfaces are its legs.
  double gap_m = 1e300;
  int64_t id_a = 0;      // object ids; -1 stands for the robot
  int64_t id_b = 0;
  double time_s = 0.0;
};

struct ScenarioReport {
  int scans = 0;
  double scan_period_s = 0.0;
  int min_statics_visible = 0;       // over all scans
  double mean_statics_visible = 0.0;
  double min_statics_visible_time_s = 0.0;  // first scan with the minimum
  int scans_with_fewer_than_3_statics = 0;
  int min_movers_visible = 0;        // over all scans
  double mean_movers_visible = 0.0;
  double robot_path_m = 0.0;
  double robot_max_speed_mps = 0.0;
  ClosestApproach mover_mover;   // the surfaces (discs, legs) of two movers
  ClosestApproach mover_static;  // a mover's surface (disc or leg) and a static circle or segment
  ClosestApproach robot_static;  // the robot (robot_radius_m) and a static circle or segment
  ClosestApproach robot_mover;   // the robot and a mover's surface
  // Laser figures (valid beams of every scan): share on static segments (walls, furniture
  // sides), on walls alone, and on legs.
  int64_t valid_beams = 0;
  int64_t beams_on_segments = 0;
  int64_t beams_on_walls = 0;
  int64_t beams_on_legs = 0;
  int64_t mixed_pixels = 0;  // valid beams flagged mixed_pixel (scan output)
  int64_t dropouts = 0;      // beams that hit a surface but gave no return (scan output)
  // Legs of people whose centre is in view: (leg, scan) pairs, how many of them had at least one
  // beam, at least three, and how many were hidden while the other leg of the person had beams
  // (one leg hiding the other, or something in front of one leg only).
  int64_t legs_in_view = 0;
  int64_t legs_with_beams = 0;
  int64_t legs_with_3_beams = 0;
  int64_t legs_hidden_while_other_seen = 0;
  int64_t beams_on_legs_in_view = 0;  // sum of beams over those pairs
  std::vector<MoverReport> movers;  // in order of first appearance
  std::vector<OcclusionEpisode> occlusions;  // in order of their start
};

class ScenarioReporter {
 public:
  // `robot_radius_m`: the robot's body as a disc, for robot gaps (about the P3-DX's swing
  // radius; its body is 0.455 x 0.381 m).
  ScenarioReporter(const LaserSpec& laser, double robot_radius_m = 0.26);
  void AddScan(const SensorFrame& frame);
  ScenarioReport Finish() const;

 private:
  struct MoverState {
    MoverReport report;
    bool occluded = false;
    size_t episode = 0;  // index into report_.occlusions while occluded
    double occlusion_s = 0.0;
    double visible_run_s = 0.0;
  };
  LaserSpec laser_;
  double robot_radius_m_;
  double period_s_;
  ScenarioReport report_;
  int64_t statics_visible_sum_ = 0;
  int64_t movers_visible_sum_ = 0;
  bool have_previous_ = false;
  Pose2D previous_pose_;
  std::vector<int64_t> order_;
  std::map<int64_t, MoverState> movers_;
};

// Runs a whole scenario (with features when its output has them, else scans) and reports on it.
ScenarioReport ReportScenario(const Scenario& scenario, uint64_t seed);

// The report as human-readable text, one mover per line.
std::string FormatScenarioReport(const ScenarioReport& report);

}  // namespace slammtt
