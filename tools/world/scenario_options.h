// The options schemas of a scenario's settings (common/options_schema.h): the scalar keys of the
// scenario file's top level and of its `laser:`, `features:`, `odometry:`, `legs:` and `robot:`
// sections, each listed once with its range and one line of documentation. The scenario loader
// reads them (tools/world/scenario_loader.h), FindScenarioProblems checks them (scenario.h) and
// docs/world.md carries their tables (slammtt-world --options-table). The geometry of a scenario
// (robot.start, robot.profile, robot.waypoints, statics, movers, crowd) and `people` are its
// format, read by the loader itself.
//
// Keys are the field names, without the name of a nested struct (LaserSpec::artefacts' fields
// are keys of `laser:`). Every field holds the unit its key says (laser angles in degrees),
// except RobotMotionSpec::max_angular_radps, written in degrees (`max_angular_degps`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "common/options_schema.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Top level: duration_s, start_utime, output.
void VisitScenarioSettings(OptionVisitor* visitor, Scenario* scenario);
void VisitLaserSpec(OptionVisitor* visitor, LaserSpec* laser);
void VisitFeatureSpec(OptionVisitor* visitor, FeatureSpec* features);
void VisitOdometrySpec(OptionVisitor* visitor, OdometrySpec* odometry);
void VisitLegSpec(OptionVisitor* visitor, LegSpec* legs);
void VisitScatteredLandmarksSpec(OptionVisitor* visitor, ScatteredLandmarksSpec* landmarks);
// The waypoint controller's settings and `loop` (not start, profile, waypoints).
void VisitRobotMotionSettings(OptionVisitor* visitor, RobotMotionSpec* robot);

// Shows every section of `scenario`, in the order of the file, to the visitor that
// `visitor_for(section)` returns: section "" (the top level), "laser", "features", "odometry",
// "robot", "legs".
template <typename VisitorFor>
void VisitScenarioSections(Scenario* scenario, VisitorFor&& visitor_for) {
  VisitScenarioSettings(visitor_for(""), scenario);
  VisitLaserSpec(visitor_for("laser"), &scenario->laser);
  VisitFeatureSpec(visitor_for("features"), &scenario->features);
  VisitOdometrySpec(visitor_for("odometry"), &scenario->odometry);
  VisitRobotMotionSettings(visitor_for("robot"), &scenario->robot);
  VisitLegSpec(visitor_for("legs"), &scenario->legs);
  VisitScatteredLandmarksSpec(visitor_for("scattered_landmarks"), &scenario->scattered_landmarks);
}

// The first value of `scenario` outside its range, as ("laser.fov_deg", "must be in (0, 360],
// got 400"); both empty when every value is valid.
std::pair<std::string, std::string> FindScenarioSettingsProblem(const Scenario& scenario);

// The tables of every section's keys, each under a line naming it ("Top level:",
// "`laser:`", ...), for docs/world.md ("Scenario files"; slammtt-world --options-table).
std::vector<std::pair<std::string, std::string>> ScenarioOptionsTables();
std::string ScenarioOptionsMarkdown();

}  // namespace slammtt
