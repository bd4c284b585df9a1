// slammtt-estimator: ODOMETRY, FEATURES and LASER_GEOMETRY in; POSE, MAP, TRACKS,
// ESTIMATOR_STATUS and STAGE_TIMING out (paper Algorithm 2). Thin: the work is in EstimatorStage
// (estimator/estimator_stage.h), which slammtt-replay runs too.
#include <algorithm>
#include <cmath>
#include <iostream>

#include "estimator/estimator_stage.h"
#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/stage.h"

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-estimator", [](int c, char** v) {
    slammtt::CommandLine command_line(
        "slammtt-estimator", "[options]",
        "EKF SLAM with moving-object tracking and ML-RANSAC data association (paper Algorithm "
        "2). Subscribes odometry, features and laser_geometry (the laser's mount, view and "
        "range, taken where --config does not give them); publishes pose, map, tracks, "
        "estimator_status and stage_timing; options in the `estimator:` section of --config "
        "(docs/estimator.md).");
    slammtt::AddStandardOptions(&command_line);
    command_line.AddFlag("options-table",
                         "print the table of every key of the estimator: section (Markdown, "
                         "docs/estimator.md) and exit");
    if (!command_line.Parse(c, v)) return 0;
    if (command_line.Flag("options-table")) {
      std::cout << slammtt::EstimatorStageOptionsTable();
      return 0;
    }
    const slammtt::ProcessSettings settings = slammtt::LoadProcessSettings(command_line);
    slammtt::EstimatorStage stage(settings);
    slammtt::LcmBus bus(settings.lcm_url);
    slammtt::SteadyMonotonicClock clock;  // no timer reads it: stages run on message time
    slammtt::EventLoop loop(&bus, &clock);
    slammtt::LiveStageRunner runner(&bus);
    runner.Add(&stage);
    slammtt::LogInfo() << "estimating from " << settings.channels.Get("odometry") << " and "
                       << settings.channels.Get("features") << " on " << settings.lcm_url
                       << " (mode "
                       << slammtt::AssociationModeName(stage.estimator().options().mode) << ")";
    loop.Run();
    const slammtt::EstimatorCounters& n = stage.estimator().counters();
    slammtt::LogInfo() << "stopped: " << n.scans_processed << " scans, " << n.odometry_processed
                       << " odometry messages, " << n.features_rejected << " features rejected, "
                       << n.messages_out_of_order << " messages out of order, " << n.restarts
                       << " restarts (new time base), "
                       << stage.counters().messages_undecodable << " undecodable, "
                       << runner.handler_errors() << " handler errors";
    // The odometry's heading drift estimate (docs/estimator.md): well away from zero, it says
    // the wheels' effective diameters differ and the base's odometry wants a calibration.
    const slammtt::SlamState& state = stage.estimator().state();
    slammtt::LogInfo() << "odometry heading drift estimate: " << state.heading_drift_rad_per_m()
                       << " rad/m, sigma "
                       << std::sqrt(std::max(0.0, state.heading_drift_variance())) << " rad/m";
    return 0;
  });
}
