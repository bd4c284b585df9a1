// Streaming decoders for the two scan replies of the RPLIDAR A2: standard 5-byte nodes and
// legacy express 84-byte capsules. Feed them the bytes as they arrive, in any chunking; they
// hand back samples. Pure: the caller passes the host time the chunk arrived.
//
// What is a valid sample, and how a decoder finds its way back after bad bytes:
//
// Standard node (protocol document "Scan request and response", sl_lidar_cmd.h
// sl_lidar_response_measurement_node_t; handler_normalnode.cpp):
//   byte 0: bit 0 S (new revolution), bit 1 !S (inverse of S), bits 7..2 quality
//   byte 1: bit 0 C (check bit, always 1), bits 7..1 angle_q6 bits 6..0
//   byte 2: angle_q6 bits 14..7;  bytes 3..4: distance_q2, little-endian
//   angle = angle_q6 / 64 degrees, distance = distance_q2 / 4 mm, 0 = no return.
// A node passes when S != !S, C = 1 and (our addition) the angle is below 360 degrees. Those
// are only 2 check bits, so one random 5-byte window in 4 passes them; the SDK accepts it. We
// also require the sequence to make sense: consecutive passing nodes form a run when each
// angle steps forward by at most max_step_deg (or back by at most max_back_step_deg) from the
// one before; a node is emitted only once `lookahead` nodes after it have continued its run,
// and a new run (at start, or after a glitch) must first reach `confirm_run` nodes. A glitch
// (bytes that fail the checks, or a node that breaks the sequence) drops the nodes still
// waiting for successors, and the first node of the run after a glitch (it may straddle the
// glitch: a real tail behind garbage). Cost: the output lags the input by `lookahead` nodes
// (1 ms at 2000 samples/s) and a glitch costs about 3 real nodes. What remains: corruption
// that keeps the check bits and the angle plausible, e.g. a changed distance byte, cannot be
// seen in this format at all; docs/rplidar.md gives the rate we measured.
//
// Express capsule (protocol document "Express scan"; sl_lidar_response_capsule_measurement_
// nodes_t; handler_capsules.cpp, which is what we follow bit for bit):
//   byte 0: 0xA in the high nibble, checksum bits 3..0 in the low nibble
//   byte 1: 0x5 in the high nibble, checksum bits 7..4 in the low nibble
//   bytes 2..3: start angle w in q6 (15 bits, LE), bit 15 = S (scan (re)started)
//   bytes 4..83: 16 cabins of 5 bytes: distance1 (u16 LE, bits 1..0 = dtheta1 bits 5..4),
//     distance2 (likewise), then dtheta1 bits 3..0 | dtheta2 bits 3..0 << 4.
//   checksum = XOR of bytes 2..83.
// Sample k (0..31) of capsule i: angle = w_i + k * AngleDiff(w_i, w_{i+1}) / 32 - dtheta_k / 8
// degrees, in the SDK's fixed point (q16 accumulation, >> 10 to q6); dtheta is read unsigned,
// as the SDK does (the protocol document calls its top bit a sign: Slamtec/rplidar_sdk issue
// #87 leaves it open); distance = field with its 2 low bits cleared, in q2 (1 mm steps). A
// capsule is decoded only when the next valid capsule has arrived; a bad checksum, lost sync
// nibbles or a capsule with S set also drop the waiting capsule (its angle span is unknown).
// Our addition: a span more than 1.5 times the previous one means a capsule vanished whole
// (nothing else tells: no bytes were corrupt), so the waiting capsule is dropped rather than
// decoded with 32 stretched angles (the rotation speed changes far less in 8 ms).
// Capsules carry no quality: like the SDK we report 47 (of 63) for a return, 0 for none.
// Revolutions are cut per sample when the interpolated angle wraps past 360 degrees (the
// capsule's S bit is not a revolution mark): the first sample at or past 360 starts the new
// one. The SDK's flag looks one increment ahead and marks the sample just before the wrap
// (handler_capsules.cpp, syncBit), so its revolutions start one sample earlier; the samples
// and their angles are the same.
//
// Counters follow lidar_status_t: a resync is one episode of discarding bytes (or untrusted
// nodes) until valid data is found again; a checksum error is one whole express capsule that
// failed its checksum: a window that fails where a capsule was due (right after the last good
// one), or a whole number of capsules before the next good one. A window that matched the two
// sync nibbles by chance while the decoder searched (1 in 256: about 0.3 inside each damaged
// capsule) is not one, and neither is a capsule that lost bytes (it is a resync).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "drivers/rplidar/rplidar_protocol.h"

namespace slammtt {
namespace rplidar {

inline constexpr uint32_t kFullTurnQ6 = 360 * 64;

// One measurement as the device reports it.
struct ScanSample {
  uint16_t angle_q6 = 0;      // degrees * 64, clockwise from the device's 0, [0, 23040)
  uint16_t distance_q2 = 0;   // millimetres * 4; 0 = no return
  uint8_t quality = 0;        // 0..63
  bool start_of_revolution = false;
  int64_t arrival_us = 0;     // host time of the chunk that completed its node or capsule
  uint64_t source_offset = 0; // stream offset of its node's or capsule's first byte

  double AngleDeg() const { return angle_q6 / 64.0; }
  double DistanceMm() const { return distance_q2 / 4.0; }
};

struct DecoderCounters {
  int64_t samples = 0;            // samples handed out
  int64_t resyncs = 0;            // episodes of discarding bytes or untrusted nodes
  int64_t skipped_bytes = 0;      // bytes that belonged to no accepted node or capsule
  int64_t checksum_errors = 0;    // express capsules with a bad checksum
  int64_t rejected_nodes = 0;     // standard nodes that passed the checks but not the sequence
  int64_t dropped_capsules = 0;   // express capsules never decoded (no valid successor)
};

// The result of the standard node checks alone (no sequence rule): for tests and tools.
std::optional<ScanSample> ParseStandardNode(const uint8_t* bytes);

struct StandardDecoderOptions {
  double max_step_deg = 15.0;      // forward angle step allowed between consecutive nodes
  double max_back_step_deg = 5.0;  // backward step allowed (angles of real nodes jitter)
  int confirm_run = 3;             // passing nodes in a row before a new run is trusted
  int lookahead = 2;               // successors a node needs in its run before it is emitted
};

class StandardNodeDecoder {
 public:
  explicit StandardNodeDecoder(const StandardDecoderOptions& options = {});
  // Appends the samples that became certain to `out`.
  void Feed(const uint8_t* data, size_t size, int64_t arrival_us, std::vector<ScanSample>* out);
  // Forgets buffered bytes and the current run (a new scan starts); offsets keep counting.
  void Reset();
  const DecoderCounters& counters() const { return counters_; }

 private:
  bool Continues(const ScanSample& previous, const ScanSample& next) const;
  void BreakRun();
  void LoseSync();

  StandardDecoderOptions options_;
  int32_t max_step_q6_;
  int32_t max_back_step_q6_;
  std::vector<uint8_t> buffer_;
  uint64_t buffer_offset_ = 0;  // stream offset of buffer_[0]
  std::deque<ScanSample> run_;  // passing nodes not yet emitted, in order
  bool trusted_ = false;        // the run reached confirm_run
  bool after_glitch_ = false;   // bytes or nodes were discarded since the last run began
  bool seam_ = false;           // the run's first node follows a glitch: never emitted
  bool in_sync_ = true;
  DecoderCounters counters_;
};

class ExpressCapsuleDecoder {
 public:
  void Feed(const uint8_t* data, size_t size, int64_t arrival_us, std::vector<ScanSample>* out);
  void Reset();
  const DecoderCounters& counters() const { return counters_; }

 private:
  struct Capsule {
    uint16_t start_angle_q6 = 0;
    bool start_flag = false;
    std::array<uint8_t, 80> cabins = {};
    uint64_t offset = 0;
    int64_t arrival_us = 0;
  };
  void Decode(const Capsule& capsule, uint16_t next_start_angle_q6, std::vector<ScanSample>* out);
  void Skip(size_t count);
  void DropWaiting();
  static int64_t AngleSpanQ6(uint16_t from_q6, uint16_t to_q6);

  std::vector<uint8_t> buffer_;
  uint64_t buffer_offset_ = 0;
  std::optional<Capsule> waiting_;  // decoded when the next valid capsule arrives
  int64_t previous_base_q16_ = -1;  // interpolated angle of the last sample, for the wrap
  int64_t previous_span_q6_ = 0;    // angle between the last two decoded capsules, 0: unknown
  uint64_t expected_offset_ = 0;    // where the next capsule is due: after the last one
  static constexpr size_t kMaxFailedOffsets = 64;
  std::vector<uint64_t> failed_offsets_;  // windows that failed since the last good capsule
  bool in_sync_ = true;
  DecoderCounters counters_;
};

// Splits samples into revolutions at start_of_revolution, and also where the angle wraps past
// 360 degrees (it falls by more than half a turn from one sample to the next) once the
// revolution has covered more than half a turn: a fault that corrupts the node with the
// standard scan's S bit must not give a 720-degree scan. A start mark within a quarter turn
// after a start made by a wrap is that same start (a mark one node late), not a new one.
// Samples before the first start are a partial revolution and are dropped (as the SDK's scan
// holder does); so is a revolution that exceeds `max_samples` without a start, counted in
// overlong().
class RevolutionAssembler {
 public:
  explicit RevolutionAssembler(size_t max_samples = 8192) : max_samples_(max_samples) {}
  // Returns the finished revolution when `sample` starts the next one.
  std::optional<std::vector<ScanSample>> Add(const ScanSample& sample);
  // Drops the partial revolution: after a link loss the next one starts at the next start.
  void Reset();
  int64_t dropped_samples() const { return dropped_samples_; }
  int64_t overlong() const { return overlong_; }
  // Revolutions started where the angle wrapped without a start mark (a lost S bit).
  int64_t starts_without_mark() const { return starts_without_mark_; }

 private:
  // Whether `sample` starts a revolution; updates the angle covered since the last start.
  bool StartsRevolution(const ScanSample& sample);

  size_t max_samples_;
  std::vector<ScanSample> current_;
  bool started_ = false;
  bool have_last_angle_ = false;
  uint16_t last_angle_q6_ = 0;
  int64_t covered_q6_ = 0;          // forward angle since the last start
  bool started_by_wrap_ = false;
  int64_t dropped_samples_ = 0;
  int64_t overlong_ = 0;
  int64_t starts_without_mark_ = 0;
};

}  // namespace rplidar
}  // namespace slammtt
