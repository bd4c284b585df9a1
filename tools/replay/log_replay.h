// Deterministic replay: the processing stages of the stack run in-process on the events of a log,
// in log order, and everything they publish is written to an output log. The stage objects are
// the very ones the live processes run (runtime/stage.h), so a replay computes what the live
// stack computes, except that nothing here depends on thread scheduling or network timing.
//
// Semantics (docs/tools.md):
// - The input is scanned once (log_scan.h) to learn its channels. A stage runs when one of its
//   input channels is available: present in the input or published by another running stage
//   (so the estimator runs on FEATURES that the segmenter makes from LASER_SCAN, and the
//   segmenter is skipped on a FEATURES-only log from the synthetic world).
// - Events are handled in log order. Each input event is copied to the output with its
//   timestamp, unless its channel is one that a running stage produces: then the recomputed
//   output replaces it, and the recorded event is neither copied nor fed to any stage (FEATURES
//   of the input are dropped when the segmenter runs; the estimator sees only the new ones).
// - What a stage publishes is written at once, with the timestamp of the input event that caused
//   it, and handed to every running stage that consumes that channel (in stage order) as soon
//   as the producing stage returns, as a separate process on the live bus would get it; so a
//   stage's STAGE_TIMING never includes the work of its consumers.
// - STAGE_TIMING describes the machine, not the world: it goes to a separate timing output so
//   that the main output is byte-identical run after run. Input STAGE_TIMING events are dropped
//   whenever a stage runs (they describe another run).
// - A stage that throws (a bug: stages report bad messages themselves) is counted and reported
//   with the event number, and the replay goes on, as LiveStageRunner does live. So is a stage
//   that publishes on a channel its OutputChannels() does not declare (the message is dropped).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "runtime/log_scan.h"
#include "runtime/stage.h"

namespace slammtt {

struct StageReplayStats {
  std::string name;
  bool runs = false;
  int64_t messages_handled = 0;
  int64_t messages_published = 0;
  int64_t timing_messages = 0;
  int64_t errors = 0;  // exceptions escaping Handle()
};

// Where replayed events go: (timestamp [us], channel, bytes, size).
using EventWriter = std::function<void(int64_t, const std::string&, const void*, int)>;

class LogReplay {
 public:
  // `timing_channel`: the channel name of STAGE_TIMING.
  // The stages' OutputChannels() are the channels of the input that they replace.
  LogReplay(std::vector<std::unique_ptr<Stage>> stages, std::string timing_channel);

  // Decides which stages run, given the channels present in the input.
  void Plan(const std::set<std::string>& input_channels);

  // Handles one input event: copies it (unless replaced), runs the stages on it and writes what
  // they publish. `timing` may be empty (timing messages are then discarded).
  void HandleEvent(const LogEvent& event, const EventWriter& output, const EventWriter& timing);

  const std::vector<StageReplayStats>& stats() const { return stats_; }
  // Channels the running stages produce (the replaced ones), for reports.
  const std::set<std::string>& produced_channels() const { return produced_; }

 private:
  class CascadeSink;
  void Deliver(const std::string& channel, const void* data, int size, int64_t timestamp_us,
               int64_t eventnum, const EventWriter& output, const EventWriter& timing,
               int depth);

  std::vector<std::unique_ptr<Stage>> stages_;
  std::vector<StageReplayStats> stats_;
  std::vector<std::set<std::string>> outputs_;  // each stage's OutputChannels()
  std::string timing_channel_;
  std::set<std::string> produced_;
  bool planned_ = false;
};

struct ReplayProgress {
  int64_t events_done = 0;
  int64_t events_total = 0;
  int64_t log_time_us = 0;   // timestamp of the last event, from the first one
  int64_t log_span_us = 0;   // first to last timestamp of the input
};

struct ReplayFileOptions {
  std::string timing_channel = "STAGE_TIMING";
  std::string timing_path;             // empty: no timing log
  bool truncated_tail_is_error = false;
  // Progress is reported every this many events or log seconds, whichever comes first.
  int64_t progress_every_events = 20000;
  double progress_every_log_s = 30.0;
  std::function<void(const ReplayProgress&)> on_progress;
  // Checked before every event: true stops the replay (a SIGINT or SIGTERM), with `error`
  // saying so and no output left behind.
  std::function<bool()> should_stop;
  // Channels taken out of the input before anything sees it: neither copied nor handed to a
  // stage, as if the log had never held them (e.g. ODOMETRY, to run the estimator as on a robot
  // without wheel odometry). Their events still count in events_read.
  std::set<std::string> dropped_channels;
};

struct ReplayFileResult {
  LogScan input;
  int64_t events_read = 0;
  int64_t events_written = 0;
  int64_t timing_events_written = 0;
  std::vector<StageReplayStats> stages;
  std::set<std::string> replaced_channels;
  // Empty when the replay succeeded; else one line (the output is then not left behind).
  std::string error;
  // A reported, tolerated problem (a truncated tail when it is not an error).
  std::string warning;
};

// Replays `input_path` into `output_path` (and the timing log when asked). On success both logs
// are in place; on damaged input (corrupt, or a truncated tail when that is an error) `error`
// says why in one line, every readable event has been processed, and no output file is left
// behind; the same when options.should_stop() asks the replay to stop. Throws
// std::runtime_error (and leaves no output either) when a file cannot be opened or created or is
// not a regular file, on a write error, and when the output would overwrite the input.
ReplayFileResult ReplayLogFile(const std::string& input_path, const std::string& output_path,
                               std::vector<std::unique_ptr<Stage>> stages,
                               const ReplayFileOptions& options);

}  // namespace slammtt
