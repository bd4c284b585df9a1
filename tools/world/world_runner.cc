#include "tools/world/world_runner.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "runtime/lcm_io.h"
#include "runtime/log.h"
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
  LogWriter log(path);
  while (!world->Done()) {
    if (ShutdownRequested()) {
      summary.interrupted = true;
      summary.wall_s = SecondsSince(start);
      return summary;  // the writer's destructor removes the partial log
    }
    const WorldEvent event = world->Next();
    for (const EncodedMessage& message :
         EncodeWorldEvent(event, scenario, channels, scenario.start_utime)) {
      log.Write(message.utime, message.channel, message.data.data(),
                static_cast<int>(message.data.size()));
      Count(message, &summary);
    }
    summary.simulated_s = static_cast<double>(event.time_us) * 1e-6;
  }
  log.Commit();
  summary.wall_s = SecondsSince(start);
  return summary;
}

namespace {

struct CommandListener {
  bool have_command = false;
  VelocityCommand command;
  SteadyClock::time_point received;
  int64_t bad_messages = 0;
};

void OnVelocityCommand(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/,
                       CommandListener* listener) {
  slammtt_msgs::velocity_command_t msg;
  if (!Decode(rbuf->data, static_cast<int>(rbuf->data_size), &msg) ||
      !std::isfinite(msg.linear_mps) || !std::isfinite(msg.angular_radps)) {
    ++listener->bad_messages;
    if (IsReportable(listener->bad_messages)) {
      LogWarning() << "ignored a malformed VELOCITY_COMMAND (" << listener->bad_messages
                   << " so far)";
    }
    return;
  }
  listener->have_command = true;
  listener->command = VelocityCommand{msg.linear_mps, msg.angular_radps};
  listener->received = SteadyClock::now();
}

}  // namespace

WorldRunSummary PublishWorldLive(WorldSimulator* world, lcm::LCM* lcm,
                                 const WorldChannels& channels, const LiveOptions& options) {
  if (!(options.rate_factor > 0.0) || !std::isfinite(options.rate_factor)) {
    throw std::invalid_argument("rate factor must be a positive number");
  }
  CommandListener listener;
  lcm::Subscription* subscription = nullptr;
  if (options.follow_commands) {
    subscription = lcm->subscribeFunction(options.velocity_command_channel, &OnVelocityCommand,
                                          &listener);
    world->SetCommandOverride(VelocityCommand{});  // stand still until commanded
  }
  const Scenario& scenario = world->scenario();
  const int64_t utime_offset = std::chrono::duration_cast<std::chrono::microseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count();
  const SteadyClock::time_point start = SteadyClock::now();
  WorldRunSummary summary;
  while (!world->Done()) {
    const auto due = start + std::chrono::microseconds(std::llround(
                                 static_cast<double>(world->NextEventTimeUs()) /
                                 options.rate_factor));
    while (!ShutdownRequested()) {
      const auto now = SteadyClock::now();
      if (now >= due) break;
      const auto wait = std::min<SteadyClock::duration>(due - now, std::chrono::milliseconds(50));
      if (options.follow_commands) {
        const int wait_ms = static_cast<int>(std::max<int64_t>(
            0, std::chrono::duration_cast<std::chrono::milliseconds>(wait).count()));
        // A signal interrupts the wait (select fails with EINTR): that is the shutdown request
        // the loop checks next, not a failure of the bus.
        errno = 0;
        if (lcm->handleTimeout(wait_ms) < 0 && errno != EINTR && !ShutdownRequested()) {
          throw std::runtime_error("LCM receive failed");
        }
      } else {
        std::this_thread::sleep_for(wait);
      }
    }
    if (ShutdownRequested()) {
      summary.interrupted = true;
      break;
    }
    if (options.follow_commands) {
      const bool fresh =
          listener.have_command &&
          std::chrono::duration<double>(SteadyClock::now() - listener.received).count() <=
              options.command_timeout_s;
      world->SetCommandOverride(fresh ? listener.command : VelocityCommand{});
    }
    const WorldEvent event = world->Next();
    for (const EncodedMessage& message :
         EncodeWorldEvent(event, scenario, channels, utime_offset)) {
      if (lcm->publish(message.channel, message.data.data(),
                       static_cast<unsigned int>(message.data.size())) != 0) {
        throw std::runtime_error("LCM publish failed on " + message.channel);
      }
      Count(message, &summary);
    }
    summary.simulated_s = static_cast<double>(event.time_us) * 1e-6;
  }
  if (subscription != nullptr) lcm->unsubscribe(subscription);
  summary.wall_s = SecondsSince(start);
  return summary;
}

}  // namespace slammtt
