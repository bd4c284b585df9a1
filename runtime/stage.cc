#include "runtime/stage.h"

#include <exception>

#include "runtime/log.h"
#include "slammtt_msgs/stage_timing_t.hpp"

namespace slammtt {

StageTimer::StageTimer(std::string stage, int64_t utime)
    : stage_(std::move(stage)), utime_(utime), start_(Clock::now()), lap_start_(start_) {}

void StageTimer::Lap(const std::string& name) {
  const Clock::time_point now = Clock::now();
  substages_.emplace_back(
      name, std::chrono::duration_cast<std::chrono::nanoseconds>(now - lap_start_).count());
  lap_start_ = now;
}

void StageTimer::Count(const std::string& name, int64_t value) {
  counters_.emplace_back(name, value);
}

void StageTimer::AddSubstage(const std::string& name, int64_t duration_ns) {
  substages_.emplace_back(name, duration_ns);
}

slammtt_msgs::stage_timing_t StageTimer::Finish() const {
  slammtt_msgs::stage_timing_t msg;
  msg.utime = utime_;
  msg.stage = stage_;
  msg.total_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
  msg.num_substages = static_cast<int32_t>(substages_.size());
  for (const auto& [name, ns] : substages_) {
    msg.substage.push_back(name);
    msg.substage_ns.push_back(ns);
  }
  msg.num_counters = static_cast<int32_t>(counters_.size());
  for (const auto& [name, value] : counters_) {
    msg.counter_name.push_back(name);
    msg.counter_value.push_back(value);
  }
  return msg;
}

LiveStageRunner::LiveStageRunner(Bus* bus) : bus_(bus) {}

void LiveStageRunner::Add(Stage* stage) {
  stages_.push_back(stage);
  for (const std::string& channel : stage->InputChannels()) {
    bool already = false;
    for (const std::string& c : subscribed_) already = already || (c == channel);
    if (already) continue;  // one subscription per channel; the handler serves every stage
    subscribed_.push_back(channel);
    bus_->SubscribeBytes(channel, [this](const std::string& ch, const void* data, int size) {
      HandleMessage(ch, data, size);
    });
  }
}

void LiveStageRunner::HandleMessage(const std::string& channel, const void* data, int size) {
  for (Stage* s : stages_) {
    bool wants = false;
    for (const std::string& c : s->InputChannels()) wants = wants || (c == channel);
    if (!wants) continue;
    try {
      s->Handle(channel, data, size, *bus_);
    } catch (const std::exception& e) {
      ++handler_errors_;
      LogError() << s->Name() << ": message on " << channel << " failed: " << e.what();
    }
  }
}

}  // namespace slammtt
