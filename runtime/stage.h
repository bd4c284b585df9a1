// A processing stage (segmenter, estimator, ...) as both the live process and the deterministic
// replay run it: the same object receives the same messages in the same order and publishes
// through a MessageSink, so a replay computes exactly what the live process computes (Drake's
// DrakeLcmLog idea). A stage never reads the wall clock for its results; it only measures its
// own duration for STAGE_TIMING, which replay keeps apart from the deterministic output.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "runtime/bus.h"
#include "runtime/lcm_io.h"

namespace slammtt_msgs {
class stage_timing_t;
}

namespace slammtt {

class Stage {
 public:
  virtual ~Stage() = default;
  // Short name used in logs and STAGE_TIMING ("segmenter").
  virtual std::string Name() const = 0;
  // Channels this stage consumes.
  virtual std::vector<std::string> InputChannels() const = 0;
  // Channels this stage publishes, except STAGE_TIMING (which every stage may publish and
  // replay keeps apart): replay replaces these channels of its input with the recomputed ones.
  virtual std::vector<std::string> OutputChannels() const = 0;
  // Handles one message. A malformed or unusable message is counted and reported by the stage
  // (a status message or a log line), never thrown out of here: one bad message must not stop
  // a live process or a replay.
  virtual void Handle(const std::string& channel, const void* data, int size,
                      MessageSink& out) = 0;
};

// Measures one handling of a message, with sub-stages and work counters, into stage_timing_t.
//   StageTimer timer("estimator", scan.utime);
//   ... predict ...;  timer.Lap("predict");
//   ... gating ...;   timer.Lap("gating");
//   timer.Count("hypotheses", n);
//   out.PublishMessage(channels.Get("stage_timing"), timer.Finish());
class StageTimer {
 public:
  StageTimer(std::string stage, int64_t utime);
  // Closes the current sub-stage under `name` and starts the next one.
  void Lap(const std::string& name);
  // Adds a named amount of work (beams, features, hypotheses).
  void Count(const std::string& name, int64_t value);
  // Adds a sub-stage whose duration the caller measured (e.g. inside a library callback).
  void AddSubstage(const std::string& name, int64_t duration_ns);
  slammtt_msgs::stage_timing_t Finish() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::string stage_;
  int64_t utime_;
  Clock::time_point start_;
  Clock::time_point lap_start_;
  std::vector<std::pair<std::string, int64_t>> substages_;
  std::vector<std::pair<std::string, int64_t>> counters_;
};

// Runs stages on a bus (LCM live; any Bus in tests): subscribes every input channel, hands each
// message to the stages that consume it and publishes their outputs on the same bus. An
// exception escaping a stage (a bug) is logged with the channel and counted, and the process
// goes on. The process's EventLoop (event_loop.h) delivers the messages.
class LiveStageRunner {
 public:
  explicit LiveStageRunner(Bus* bus);
  void Add(Stage* stage);
  int64_t handler_errors() const { return handler_errors_; }

 private:
  void HandleMessage(const std::string& channel, const void* data, int size);

  Bus* bus_;
  std::vector<Stage*> stages_;
  std::vector<std::string> subscribed_;
  int64_t handler_errors_ = 0;
};

}  // namespace slammtt
