// slammtt-smoother: SMOOTHER_INPUT in (from slammtt-estimator); SMOOTHED_POSE, SMOOTHED_MAP,
// SMOOTHED_TRAJECTORY and
// STAGE_TIMING out (docs/smoother.md, "In the stack"). Thin: the work is in SmootherStage
// (smoother/smoother_stage.h), which slammtt-replay runs too.
#include <iostream>

#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/stage.h"
#include "smoother/smoother_stage.h"

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-smoother", [](int c, char** v) {
    slammtt::CommandLine command_line(
        "slammtt-smoother", "[options]",
        "Sparse smoothing of the estimator's trajectory and static map with CHOLMOD (issue 14). "
        "Subscribes smoother_input; publishes smoothed_pose, smoothed_map, smoothed_trajectory and "
        "stage_timing; "
        "options in the `smoother:` section of --config (docs/smoother.md).");
    slammtt::AddStandardOptions(&command_line);
    command_line.AddFlag("options-table",
                         "print the table of every key of the smoother: section (Markdown, "
                         "docs/smoother.md) and exit");
    if (!command_line.Parse(c, v)) return 0;
    if (command_line.Flag("options-table")) {
      std::cout << slammtt::SmootherOptionsTable();
      return 0;
    }
    const slammtt::ProcessSettings settings = slammtt::LoadProcessSettings(command_line);
    slammtt::SmootherStage stage(settings);
    slammtt::LcmBus bus(settings.lcm_url);
    slammtt::SteadyMonotonicClock clock;  // no timer reads it: stages run on message time
    slammtt::EventLoop loop(&bus, &clock);
    slammtt::LiveStageRunner runner(&bus);
    runner.Add(&stage);
    slammtt::LogInfo() << "smoothing from " << settings.channels.Get("smoother_input") << " on "
                       << settings.lcm_url;
    loop.Run();
    const slammtt::KeyframeSmootherCounters& n = stage.smoother().counters();
    slammtt::LogInfo() << "stopped: " << n.scans << " scans, " << n.keyframes << " keyframes, "
                       << n.observations_used << " observations used, " << n.landmarks_removed
                       << " landmarks removed, " << n.inputs_refused << " inputs refused, "
                       << n.solves_failed << " solves failed, "
                       << stage.counters().messages_undecodable << " undecodable, "
                       << runner.handler_errors() << " handler errors";
    return 0;
  });
}
