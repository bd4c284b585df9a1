// slammtt-segmenter: LASER_SCAN in, FEATURES out (paper Algorithm 1). Thin: the work is in
// SegmenterStage (perception/segmenter_stage.h), which slammtt-replay runs too.
#include <iostream>

#include "perception/segmenter_stage.h"
#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/stage.h"

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-segmenter", [](int c, char** v) {
    slammtt::CommandLine command_line(
        "slammtt-segmenter", "[options]",
        "Splits every laser scan into point features with the adaptive breakpoint detector "
        "(paper section 3, Algorithm 1). Subscribes laser_scan, publishes features and "
        "stage_timing; options in the `segmenter:` section of --config (docs/perception.md).");
    slammtt::AddStandardOptions(&command_line);
    command_line.AddFlag("options-table",
                         "print the table of every key of the segmenter: section (Markdown, "
                         "docs/perception.md) and exit");
    if (!command_line.Parse(c, v)) return 0;
    if (command_line.Flag("options-table")) {
      std::cout << slammtt::SegmenterOptionsTable();
      return 0;
    }
    const slammtt::ProcessSettings settings = slammtt::LoadProcessSettings(command_line);
    slammtt::SegmenterStage stage(settings);
    slammtt::LcmBus bus(settings.lcm_url);
    slammtt::SteadyMonotonicClock clock;  // no timer reads it: stages run on message time
    slammtt::EventLoop loop(&bus, &clock);
    slammtt::LiveStageRunner runner(&bus);
    runner.Add(&stage);
    slammtt::LogInfo() << "segmenting " << settings.channels.Get("laser_scan") << " into "
                       << settings.channels.Get("features") << " on " << settings.lcm_url
                       << " (centre rule "
                       << slammtt::CentreRuleName(stage.segmenter().options().centre_rule) << ")";
    loop.Run();
    const slammtt::SegmenterStageCounters& n = stage.counters();
    slammtt::LogInfo() << "stopped: " << n.scans_handled << " scans, " << n.features_published
                       << " features, " << n.scans_rejected << " messages rejected, "
                       << runner.handler_errors() << " handler errors";
    return 0;
  });
}
