// Runs a WorldSimulator to its end, in one of the two pacing modes of slammtt-world:
//   - as fast as possible into an LCM log (deterministic: the same scenario and seed give the
//     same bytes; utime = scenario.start_utime + simulated time);
//   - in real time on a live LCM bus (utime = wall clock at start + simulated time, so the first
//     message carries the current time and lcm-logger logs look live), optionally faster than
//     real time and optionally driving the robot from VELOCITY_COMMAND.
// The wall clock is read here only for pacing and the summary, never for message contents.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "runtime/event_loop.h"
#include "tools/world/world_messages.h"
#include "tools/world/world_simulator.h"

namespace slammtt {

struct WorldRunSummary {
  int64_t messages = 0;
  std::map<std::string, int64_t> messages_per_channel;
  double simulated_s = 0.0;
  double wall_s = 0.0;
  bool interrupted = false;  // shutdown was requested before the end
};

// Publishes every event into the log at `path` (a LogBus with that output: the file appears
// only when complete). On an error or a shutdown request nothing is left at `path` nor at "path.partial":
// errors throw; a shutdown returns with interrupted = true.
WorldRunSummary WriteWorldLog(WorldSimulator* world, const WorldChannels& channels,
                              const std::string& path);

struct LiveOptions {
  double rate_factor = 1.0;       // simulated seconds per wall second, > 0
  bool follow_commands = false;   // drive the robot from VELOCITY_COMMAND instead of the scenario
  std::string velocity_command_channel = "VELOCITY_COMMAND";
  double command_timeout_s = 0.5; // (wall) without a command the robot stops, like the base
};

// Publishes every event on the loop's bus at its simulated time divided by rate_factor after
// the start, by the loop's clock (the steady clock live), handling the bus (VELOCITY_COMMAND)
// while it waits. Returns at the end or when shutdown is requested; throws when a publish is
// lost (the bus's failed_publishes() grows).
WorldRunSummary PublishWorldLive(WorldSimulator* world, EventLoop* loop,
                                 const WorldChannels& channels, const LiveOptions& options);

}  // namespace slammtt
