#include "tools/world/world_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "runtime/bus.h"
#include "runtime/log.h"
#include "runtime/log_bus.h"
#include "runtime/shutdown.h"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {

namespace {

using SteadyClock = std::chrono::steady_clock;

double SecondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

void Count(const EncodedMessage& message, WorldRunSummary* summary) {
  ++summary->messages;
  ++summary->messages_per_channel[message.channel];
}

}  // namespace

WorldRunSummary WriteWorldLog(WorldSimulator* world, const WorldChannels& channels,
                              const std::string& path) {
  const SteadyClock::time_point start = SteadyClock::now();
  WorldRunSummary summary;
  const Scenario& scenario = world->scenario();
  LogBus log("", path);  // the bus with a log file as its output
  while (!world->Done()) {
    if (ShutdownRequested()) {
      summary.interrupted = true;
      summary.wall_s = SecondsSince(start);
      return summary;  // the bus's destructor removes the partial log
    }
    const WorldEvent event = world->Next();
    for (const EncodedMessage& message :
         EncodeWorldEvent(event, scenario, channels, scenario.start_utime)) {
      log.SetTimestamp(message.utime);
      log.Publish(message.channel, message.data.data(), static_cast<int>(message.data.size()));
      Count(message, &summary);
    }
    summary.simulated_s = static_cast<double>(event.time_us) * 1e-6;
  }
  log.Commit();
  summary.wall_s = SecondsSince(start);
  return summary;
}

namespace {

// The longest single wait: the loop wakes at least this often (the shutdown request and the bus
// wake it at once anyway).
constexpr int64_t kMaxWaitUs = 50000;

struct CommandListener {
  bool have_command = false;
  VelocityCommand command;
  int64_t received_us = 0;  // the loop's clock
  int64_t bad_messages = 0;
};

}  // namespace

WorldRunSummary PublishWorldLive(WorldSimulator* world, EventLoop* loop,
                                 const WorldChannels& channels, const LiveOptions& options) {
  if (!(options.rate_factor > 0.0) || !std::isfinite(options.rate_factor)) {
    throw std::invalid_argument("rate factor must be a positive number");
  }
  Bus& bus = loop->bus();
  MonotonicClock& clock = loop->clock();
  CommandListener listener;
  int subscription = 0;
  if (options.follow_commands) {
    // An undecodable message is counted and reported by the bus; a decoded one that is not
    // finite here.
    subscription = bus.Subscribe<slammtt_msgs::velocity_command_t>(
        options.velocity_command_channel,
        [&listener, &clock](const slammtt_msgs::velocity_command_t& msg) {
          if (!std::isfinite(msg.linear_mps) || !std::isfinite(msg.angular_radps)) {
            if (IsReportable(++listener.bad_messages)) {
              LogWarning() << "ignored a malformed VELOCITY_COMMAND (" << listener.bad_messages
                           << " so far)";
            }
            return;
          }
          listener.have_command = true;
          listener.command = VelocityCommand{msg.linear_mps, msg.angular_radps};
          listener.received_us = clock.NowUs();
        });
    world->SetCommandOverride(VelocityCommand{});  // stand still until commanded
  }
  const Scenario& scenario = world->scenario();
  const int64_t utime_offset = std::chrono::duration_cast<std::chrono::microseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count();
  const int64_t start_us = clock.NowUs();
  const int64_t failed_publishes_before = bus.failed_publishes();
  WorldRunSummary summary;
  while (!world->Done()) {
    const int64_t due_us =
        start_us + std::llround(static_cast<double>(world->NextEventTimeUs()) /
                                options.rate_factor);
    while (!ShutdownRequested()) {
      const int64_t left_us = due_us - clock.NowUs();
      if (left_us <= 0) break;
      loop->HandleTimeoutUs(std::min(left_us, kMaxWaitUs));
    }
    if (ShutdownRequested()) {
      summary.interrupted = true;
      break;
    }
    if (options.follow_commands) {
      const bool fresh =
          listener.have_command &&
          static_cast<double>(clock.NowUs() - listener.received_us) * 1e-6 <=
              options.command_timeout_s;
      world->SetCommandOverride(fresh ? listener.command : VelocityCommand{});
    }
    const WorldEvent event = world->Next();
    for (const EncodedMessage& message :
         EncodeWorldEvent(event, scenario, channels, utime_offset)) {
      bus.Publish(message.channel, message.data.data(), static_cast<int>(message.data.size()));
      if (bus.failed_publishes() != failed_publishes_before) {
        throw std::runtime_error("LCM publish failed on " + message.channel);
      }
      Count(message, &summary);
    }
    summary.simulated_s = static_cast<double>(event.time_us) * 1e-6;
  }
  if (subscription != 0) bus.Unsubscribe(subscription);
  summary.wall_s = static_cast<double>(clock.NowUs() - start_us) * 1e-6;
  return summary;
}

}  // namespace slammtt
