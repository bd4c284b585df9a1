#include "tools/replay/log_replay.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <utility>

#include "runtime/log.h"
#include "runtime/log_reader.h"

namespace slammtt {
namespace {

// A chain of stages feeding each other longer than this is a loop (a stage consuming what it
// publishes, directly or through others); the message is dropped and counted as an error.
constexpr int kMaxCascadeDepth = 16;

// Thrown from the event callback when the replay is asked to stop.
struct StopRequested {};

// a - b, saturated to the int64 range (a damaged log may hold any timestamp).
int64_t SaturatingDifference(int64_t a, int64_t b) {
  int64_t difference = 0;
  if (!__builtin_sub_overflow(a, b, &difference)) return difference;
  return a > b ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
}

bool SameFile(const std::string& a, const std::string& b) {
  struct stat sa {};
  struct stat sb {};
  if (stat(a.c_str(), &sa) != 0 || stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace

// The sink a stage publishes into during one Handle(): timing to the timing output, everything
// else to the main output and on to the stages downstream.
class LogReplay::CascadeSink : public MessageSink {
 public:
  CascadeSink(LogReplay* replay, size_t stage_index, int64_t timestamp_us, int64_t eventnum,
              const EventWriter& output, const EventWriter& timing, int depth)
      : replay_(replay),
        stage_index_(stage_index),
        timestamp_us_(timestamp_us),
        eventnum_(eventnum),
        output_(output),
        timing_(timing),
        depth_(depth) {}

  void Publish(const std::string& channel, const void* data, int size) override {
    StageReplayStats& stats = replay_->stats_[stage_index_];
    if (channel == replay_->timing_channel_) {
      ++stats.timing_messages;
      if (timing_) timing_(timestamp_us_, channel, data, size);
      return;
    }
    if (replay_->outputs_[stage_index_].count(channel) == 0) {
      // The replay replaces exactly the declared channels of its input: an undeclared one would
      // appear twice (recorded and recomputed). A bug of the stage: counted, reported, dropped.
      throw std::logic_error("published on " + channel +
                             ", which its OutputChannels() does not declare");
    }
    ++stats.messages_published;
    output_(timestamp_us_, channel, data, size);
    // Downstream stages get it once this stage has returned (DeliverPending), as a separate
    // process would: the producer's STAGE_TIMING must not include its consumers' work.
    const auto* bytes = static_cast<const uint8_t*>(data);
    pending_.emplace_back(channel, std::vector<uint8_t>(bytes, bytes + size));
  }

  void DeliverPending() {
    for (const auto& [channel, bytes] : pending_) {
      replay_->Deliver(channel, bytes.data(), static_cast<int>(bytes.size()), timestamp_us_,
                       eventnum_, output_, timing_, depth_ + 1);
    }
    pending_.clear();
  }

 private:
  LogReplay* replay_;
  size_t stage_index_;
  int64_t timestamp_us_;
  int64_t eventnum_;
  const EventWriter& output_;
  const EventWriter& timing_;
  int depth_;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> pending_;
};

LogReplay::LogReplay(std::vector<std::unique_ptr<Stage>> stages, std::string timing_channel)
    : stages_(std::move(stages)), timing_channel_(std::move(timing_channel)) {
  for (const std::unique_ptr<Stage>& s : stages_) {
    if (!s) throw std::invalid_argument("replay: null stage");
    const std::vector<std::string> outputs = s->OutputChannels();
    outputs_.emplace_back(outputs.begin(), outputs.end());
    StageReplayStats stats;
    stats.name = s->Name();
    stats_.push_back(stats);
  }
}

void LogReplay::Plan(const std::set<std::string>& input_channels) {
  std::set<std::string> available = input_channels;
  for (StageReplayStats& s : stats_) s.runs = false;
  // A stage's outputs make more channels available: iterate to the fixed point.
  bool changed = true;
  while (changed) {
    changed = false;
    for (size_t k = 0; k < stages_.size(); ++k) {
      if (stats_[k].runs) continue;
      for (const std::string& channel : stages_[k]->InputChannels()) {
        if (available.count(channel) == 0) continue;
        stats_[k].runs = true;
        changed = true;
        for (const std::string& out : stages_[k]->OutputChannels()) available.insert(out);
        break;
      }
    }
  }
  produced_.clear();
  for (size_t k = 0; k < stages_.size(); ++k) {
    if (!stats_[k].runs) continue;
    const std::vector<std::string> outputs = stages_[k]->OutputChannels();
    produced_.insert(outputs.begin(), outputs.end());
    produced_.insert(timing_channel_);
  }
  planned_ = true;
}

void LogReplay::HandleEvent(const LogEvent& event, const EventWriter& output,
                            const EventWriter& timing) {
  if (!planned_) throw std::logic_error("LogReplay::HandleEvent before Plan");
  const int size = static_cast<int>(event.data.size());
  if (produced_.count(event.channel) != 0) {
    // Replaced by what a running stage computes: neither copied nor fed to the stages (the
    // estimator must see the replayed FEATURES only, not also the recorded ones).
    return;
  }
  output(event.timestamp_us, event.channel, event.data.data(), size);
  Deliver(event.channel, event.data.data(), size, event.timestamp_us, event.eventnum, output,
          timing, 0);
}

void LogReplay::Deliver(const std::string& channel, const void* data, int size,
                        int64_t timestamp_us, int64_t eventnum, const EventWriter& output,
                        const EventWriter& timing, int depth) {
  for (size_t k = 0; k < stages_.size(); ++k) {
    if (!stats_[k].runs) continue;
    Stage& stage = *stages_[k];
    bool wants = false;
    for (const std::string& c : stage.InputChannels()) wants = wants || c == channel;
    if (!wants) continue;
    if (depth > kMaxCascadeDepth) {
      ++stats_[k].errors;
      LogError() << stage.Name() << ": message on " << channel << " (input event " << eventnum
                 << ") dropped: stages feed each other in a loop";
      continue;
    }
    ++stats_[k].messages_handled;
    CascadeSink sink(this, k, timestamp_us, eventnum, output, timing, depth);
    try {
      stage.Handle(channel, data, size, sink);
    } catch (const std::exception& e) {
      ++stats_[k].errors;
      LogError() << stage.Name() << ": message on " << channel << " (input event " << eventnum
                 << ") failed: " << e.what();
    }
    sink.DeliverPending();
  }
}

ReplayFileResult ReplayLogFile(const std::string& input_path, const std::string& output_path,
                               std::vector<std::unique_ptr<Stage>> stages,
                               const ReplayFileOptions& options) {
  ReplayFileResult result;
  if (SameFile(input_path, output_path) ||
      (!options.timing_path.empty() && SameFile(input_path, options.timing_path))) {
    throw std::runtime_error(output_path + ": refusing to overwrite the input log");
  }
  if (!options.timing_path.empty() && options.timing_path == output_path) {
    throw std::runtime_error(output_path + ": the timing log must be another file");
  }
  result.input = ScanLogFile(input_path);

  LogReplay replay(std::move(stages), options.timing_channel);
  std::set<std::string> channels;
  for (const auto& entry : result.input.channels) {
    if (options.dropped_channels.count(entry.first) == 0) channels.insert(entry.first);
  }
  replay.Plan(channels);
  result.replaced_channels = replay.produced_channels();

  LogWriter writer(output_path);
  std::unique_ptr<LogWriter> timing_writer;
  if (!options.timing_path.empty()) {
    timing_writer = std::make_unique<LogWriter>(options.timing_path);
  }
  const EventWriter output = [&](int64_t ts, const std::string& ch, const void* d, int n) {
    writer.Write(ts, ch, d, n);
  };
  EventWriter timing;
  if (timing_writer) {
    timing = [&](int64_t ts, const std::string& ch, const void* d, int n) {
      timing_writer->Write(ts, ch, d, n);
    };
  }

  // Events are read through LCM's own API (what lcm-logplayer plays), with the damage report of
  // log_reader.h.
  ReplayProgress progress;
  progress.events_total = result.input.complete_events;
  progress.log_span_us =
      SaturatingDifference(result.input.last_timestamp_us, result.input.first_timestamp_us);
  // Steps of at least one event and one microsecond, and at most about 30 years of log time
  // (beyond, the conversion to int64 would overflow).
  const int64_t events_step = std::max<int64_t>(1, options.progress_every_events);
  const double time_step = options.progress_every_log_s * 1e6;
  const int64_t time_step_us =
      std::isfinite(time_step) ? static_cast<int64_t>(std::clamp(time_step, 1.0, 1e15)) : 1000000;
  // Progress is reported when the number of whole steps done (events, or log time since the
  // first event) passes the most reported so far: no counter to overflow, however far a
  // timestamp jumps, and time running backwards reports nothing.
  int64_t reported_event_steps = 0;
  int64_t reported_time_steps = 0;
  LogEvent event;
  const auto handle_event = [&](const LogEventView& e) {
    if (options.should_stop && options.should_stop()) throw StopRequested{};
    event.eventnum = e.eventnum;
    event.timestamp_us = e.timestamp_us;
    event.channel = e.channel;
    const auto* bytes = static_cast<const uint8_t*>(e.data);
    event.data.assign(bytes, bytes + e.size);
    ++result.events_read;
    if (options.dropped_channels.count(event.channel) == 0) {
      replay.HandleEvent(event, output, timing);
    }
    progress.events_done = result.events_read;
    progress.log_time_us =
        SaturatingDifference(event.timestamp_us, result.input.first_timestamp_us);
    const int64_t event_steps = progress.events_done / events_step;
    const int64_t time_steps = progress.log_time_us > 0 ? progress.log_time_us / time_step_us : 0;
    if (options.on_progress &&
        (event_steps > reported_event_steps || time_steps > reported_time_steps)) {
      options.on_progress(progress);
      reported_event_steps = event_steps;
      reported_time_steps = std::max(reported_time_steps, time_steps);
    }
  };
  LogReadResult read;
  try {
    read = ForEachLogEvent(input_path, result.input, handle_event);
  } catch (const StopRequested&) {
    result.stages = replay.stats();
    result.error = "stopped after " + std::to_string(result.events_read) + " of " +
                   std::to_string(result.input.complete_events) + " events";
    return result;  // the writers' destructors discard the unfinished files
  }
  result.stages = replay.stats();

  std::string problem;
  if (read.corrupt) {
    problem = read.problem;
  } else if (!read.problem.empty()) {  // a truncated tail
    if (options.truncated_tail_is_error) {
      problem = read.problem;
    } else {
      result.warning = read.problem + "; ignored (all " + std::to_string(result.events_read) +
                       " complete events replayed)";
    }
  }
  if (!problem.empty()) {
    result.error = problem;
    return result;  // the writers' destructors remove the partial files
  }
  result.events_written = writer.events_written();
  writer.Commit();
  if (timing_writer) {
    result.timing_events_written = timing_writer->events_written();
    timing_writer->Commit();
  }
  return result;
}

}  // namespace slammtt
