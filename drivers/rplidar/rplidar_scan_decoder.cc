#include "drivers/rplidar/rplidar_scan_decoder.h"

#include <algorithm>
#include <cmath>

namespace slammtt {
namespace rplidar {
namespace {

constexpr int64_t kFullTurnQ16 = int64_t{360} << 16;
constexpr uint8_t kExpressQuality = 47;  // handler_capsules.cpp: 0x2F << 2 on the 0..255 scale

uint16_t ReadU16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

// Floor division by 2^bits for possibly negative values (the SDK's arithmetic >> on int).
int64_t FloorShift(int64_t value, int bits) {
  const int64_t divisor = int64_t{1} << bits;
  int64_t quotient = value / divisor;
  if (value % divisor != 0 && value < 0) --quotient;
  return quotient;
}

}  // namespace

std::optional<ScanSample> ParseStandardNode(const uint8_t* bytes) {
  const uint8_t sync_quality = bytes[0];
  const bool start = (sync_quality & 0x1) != 0;
  const bool inverse_start = (sync_quality & 0x2) != 0;
  if (start == inverse_start) return std::nullopt;
  if ((bytes[1] & 0x1) == 0) return std::nullopt;
  const uint16_t angle_q6 = static_cast<uint16_t>(ReadU16(bytes + 1) >> 1);
  if (angle_q6 >= kFullTurnQ6) return std::nullopt;
  ScanSample sample;
  sample.angle_q6 = angle_q6;
  sample.distance_q2 = ReadU16(bytes + 3);
  sample.quality = static_cast<uint8_t>(sync_quality >> 2);
  sample.start_of_revolution = start;
  return sample;
}

StandardNodeDecoder::StandardNodeDecoder(const StandardDecoderOptions& options)
    : options_(options),
      max_step_q6_(static_cast<int32_t>(std::lround(options.max_step_deg * 64.0))),
      max_back_step_q6_(static_cast<int32_t>(std::lround(options.max_back_step_deg * 64.0))) {
  options_.lookahead = std::max(1, options_.lookahead);
  options_.confirm_run = std::max(options_.confirm_run, options_.lookahead + 1);
}

void StandardNodeDecoder::Reset() {
  buffer_offset_ += buffer_.size();
  buffer_.clear();
  run_.clear();
  trusted_ = false;
  in_sync_ = true;
  after_glitch_ = false;
  seam_ = false;
}

bool StandardNodeDecoder::Continues(const ScanSample& previous, const ScanSample& next) const {
  int32_t step = static_cast<int32_t>(next.angle_q6) - static_cast<int32_t>(previous.angle_q6);
  const int32_t half_turn = static_cast<int32_t>(kFullTurnQ6 / 2);
  if (step >= half_turn) step -= static_cast<int32_t>(kFullTurnQ6);
  if (step < -half_turn) step += static_cast<int32_t>(kFullTurnQ6);
  return step <= max_step_q6_ && step >= -max_back_step_q6_;
}

void StandardNodeDecoder::LoseSync() {
  if (in_sync_) ++counters_.resyncs;
  in_sync_ = false;
  after_glitch_ = true;
}

void StandardNodeDecoder::BreakRun() {
  // Nodes of the run that never got their successors are not trusted: dropped and counted.
  counters_.rejected_nodes += static_cast<int64_t>(run_.size());
  if (!run_.empty()) LoseSync();
  run_.clear();
  trusted_ = false;
}

void StandardNodeDecoder::Feed(const uint8_t* data, size_t size, int64_t arrival_us,
                               std::vector<ScanSample>* out) {
  buffer_.insert(buffer_.end(), data, data + size);
  size_t pos = 0;
  while (buffer_.size() - pos >= kStandardNodeSize) {
    std::optional<ScanSample> node = ParseStandardNode(buffer_.data() + pos);
    if (!node) {
      BreakRun();
      LoseSync();
      ++counters_.skipped_bytes;
      ++pos;
      continue;
    }
    node->arrival_us = arrival_us;
    node->source_offset = buffer_offset_ + pos;
    if (!run_.empty() && !Continues(run_.back(), *node)) BreakRun();
    if (run_.empty()) {
      // The first node after a glitch may straddle it: its tail is real, its head is not.
      seam_ = after_glitch_;
      after_glitch_ = false;
    }
    run_.push_back(*node);
    pos += kStandardNodeSize;
    if (!trusted_ && run_.size() >= static_cast<size_t>(options_.confirm_run)) {
      trusted_ = true;
      in_sync_ = true;
    }
    if (!trusted_) continue;
    while (run_.size() > static_cast<size_t>(options_.lookahead)) {
      if (seam_) {
        seam_ = false;
        ++counters_.rejected_nodes;
      } else {
        out->push_back(run_.front());
        ++counters_.samples;
      }
      run_.pop_front();
    }
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
  buffer_offset_ += pos;
}

void ExpressCapsuleDecoder::Reset() {
  buffer_offset_ += buffer_.size();
  buffer_.clear();
  waiting_.reset();
  previous_base_q16_ = -1;
  previous_span_q6_ = 0;
  expected_offset_ = buffer_offset_;
  failed_offsets_.clear();
  in_sync_ = true;
}

int64_t ExpressCapsuleDecoder::AngleSpanQ6(uint16_t from_q6, uint16_t to_q6) {
  int64_t span = int64_t{to_q6} - int64_t{from_q6};
  if (span < 0) span += kFullTurnQ6;
  return span;
}

void ExpressCapsuleDecoder::DropWaiting() {
  if (waiting_) ++counters_.dropped_capsules;
  waiting_.reset();
}

void ExpressCapsuleDecoder::Skip(size_t count) {
  if (in_sync_) ++counters_.resyncs;
  in_sync_ = false;
  counters_.skipped_bytes += static_cast<int64_t>(count);
  DropWaiting();
}

void ExpressCapsuleDecoder::Feed(const uint8_t* data, size_t size, int64_t arrival_us,
                                 std::vector<ScanSample>* out) {
  buffer_.insert(buffer_.end(), data, data + size);
  size_t pos = 0;
  while (pos < buffer_.size()) {
    const uint8_t* bytes = buffer_.data() + pos;
    const size_t left = buffer_.size() - pos;
    if ((bytes[0] >> 4) != 0xA) {
      Skip(1);
      ++pos;
      continue;
    }
    if (left < 2) break;
    if ((bytes[1] >> 4) != 0x5) {
      Skip(1);
      ++pos;
      continue;
    }
    if (left < kExpressCapsuleSize) break;
    uint8_t checksum = 0;
    for (size_t i = 2; i < kExpressCapsuleSize; ++i) checksum ^= bytes[i];
    const uint8_t received = static_cast<uint8_t>((bytes[0] & 0xF) | ((bytes[1] & 0xF) << 4));
    const uint16_t start_word = ReadU16(bytes + 2);
    if (checksum != received) {
      // Whether this was a capsule or a window whose sync nibbles matched by chance while the
      // decoder searched (1 in 256) is known only from where it sits: see CountChecksumError.
      const uint64_t offset = buffer_offset_ + pos;
      if (offset == expected_offset_) {
        ++counters_.checksum_errors;  // due right after the last good capsule
        expected_offset_ = offset + kExpressCapsuleSize;
      } else if (failed_offsets_.size() < kMaxFailedOffsets) {
        failed_offsets_.push_back(offset);  // decided when the next good capsule is found
      }
      Skip(1);
      ++pos;
      continue;
    }
    if ((start_word & 0x7FFF) >= kFullTurnQ6) {
      Skip(1);  // a start angle past 360 degrees: a false sync that passed the checksum
      ++pos;
      continue;
    }
    Capsule capsule;
    capsule.start_angle_q6 = static_cast<uint16_t>(start_word & 0x7FFF);
    capsule.start_flag = (start_word & 0x8000) != 0;
    for (size_t i = 0; i < capsule.cabins.size(); ++i) capsule.cabins[i] = bytes[4 + i];
    capsule.offset = buffer_offset_ + pos;
    capsule.arrival_us = arrival_us;
    if (capsule.start_flag) {
      // The scan (re)started: whatever waited belongs to an angle span we cannot know.
      if (waiting_) ++counters_.resyncs;
      DropWaiting();
      previous_base_q16_ = -1;
      previous_span_q6_ = 0;
    }
    if (waiting_) {
      const int64_t span_q6 = AngleSpanQ6(waiting_->start_angle_q6, capsule.start_angle_q6);
      if (previous_span_q6_ > 0 && 2 * span_q6 > 3 * previous_span_q6_) {
        // A capsule vanished whole (no bad checksum to tell): interpolating across the gap
        // would stretch 32 angles. The waiting capsule is dropped; the new one starts over.
        ++counters_.resyncs;
        DropWaiting();
        previous_base_q16_ = -1;
        previous_span_q6_ = 0;
      } else {
        Decode(*waiting_, capsule.start_angle_q6, out);
        previous_span_q6_ = span_q6;
      }
    }
    // Failed windows a whole number of capsules before this good one were capsules too.
    for (const uint64_t failed : failed_offsets_) {
      if ((capsule.offset - failed) % kExpressCapsuleSize == 0) ++counters_.checksum_errors;
    }
    failed_offsets_.clear();
    waiting_ = capsule;
    in_sync_ = true;
    pos += kExpressCapsuleSize;
    expected_offset_ = buffer_offset_ + pos;
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
  buffer_offset_ += pos;
}

void ExpressCapsuleDecoder::Decode(const Capsule& capsule, uint16_t next_start_angle_q6,
                                   std::vector<ScanSample>* out) {
  // handler_capsules.cpp _onScanNodeCapsuleData, in 64-bit arithmetic.
  const int64_t start_q8 = int64_t{capsule.start_angle_q6} << 2;
  const int64_t next_q8 = int64_t{next_start_angle_q6} << 2;
  int64_t diff_q8 = next_q8 - start_q8;
  if (start_q8 > next_q8) diff_q8 += int64_t{360} << 8;
  const int64_t increment_q16 = diff_q8 << 3;  // diff / 32 samples, in q16
  int64_t angle_q16 = start_q8 << 8;
  for (size_t cabin = 0; cabin < 16; ++cabin) {
    const uint8_t* bytes = capsule.cabins.data() + cabin * 5;
    const uint16_t field[2] = {ReadU16(bytes), ReadU16(bytes + 2)};
    const int64_t dtheta_q3[2] = {(bytes[4] & 0xF) | ((field[0] & 0x3) << 4),
                                  (bytes[4] >> 4) | ((field[1] & 0x3) << 4)};
    for (int k = 0; k < 2; ++k) {
      int64_t angle_q6 = FloorShift(angle_q16 - (dtheta_q3[k] << 13), 10);
      if (angle_q6 < 0) angle_q6 += kFullTurnQ6;
      if (angle_q6 >= kFullTurnQ6) angle_q6 -= kFullTurnQ6;
      const int64_t base_q16 = angle_q16 % kFullTurnQ16;
      ScanSample sample;
      sample.angle_q6 = static_cast<uint16_t>(angle_q6);
      sample.distance_q2 = static_cast<uint16_t>(field[k] & 0xFFFC);
      sample.quality = sample.distance_q2 != 0 ? kExpressQuality : 0;
      sample.start_of_revolution = previous_base_q16_ >= 0 && base_q16 < previous_base_q16_;
      sample.arrival_us = capsule.arrival_us;
      sample.source_offset = capsule.offset;
      previous_base_q16_ = base_q16;
      angle_q16 += increment_q16;
      out->push_back(sample);
      ++counters_.samples;
    }
  }
}

bool RevolutionAssembler::StartsRevolution(const ScanSample& sample) {
  constexpr int64_t kHalfTurnQ6 = kFullTurnQ6 / 2;
  constexpr int64_t kQuarterTurnQ6 = kFullTurnQ6 / 4;
  bool wrapped = false;
  if (have_last_angle_) {
    const int64_t step = (int64_t{sample.angle_q6} - last_angle_q6_ + kFullTurnQ6) % kFullTurnQ6;
    if (step < kHalfTurnQ6) covered_q6_ += step;  // a step back is jitter, not coverage
    wrapped = int64_t{sample.angle_q6} + kHalfTurnQ6 < int64_t{last_angle_q6_};
  }
  have_last_angle_ = true;
  last_angle_q6_ = sample.angle_q6;
  bool start = false;
  if (sample.start_of_revolution) {
    start = !(started_by_wrap_ && covered_q6_ < kQuarterTurnQ6);
    if (start) started_by_wrap_ = false;
  } else if (wrapped && (!started_ || covered_q6_ > kHalfTurnQ6)) {
    start = true;
    started_by_wrap_ = true;
    if (started_) ++starts_without_mark_;
  }
  if (start) covered_q6_ = 0;
  return start;
}

std::optional<std::vector<ScanSample>> RevolutionAssembler::Add(const ScanSample& sample) {
  std::optional<std::vector<ScanSample>> finished;
  if (StartsRevolution(sample)) {
    if (started_ && !current_.empty()) finished = std::move(current_);
    current_.clear();
    started_ = true;
  }
  if (!started_) {
    ++dropped_samples_;
    return finished;
  }
  if (current_.size() >= max_samples_) {
    // No start mark for far longer than a revolution: drop it and wait for the next start.
    dropped_samples_ += static_cast<int64_t>(current_.size()) + 1;
    ++overlong_;
    current_.clear();
    started_ = false;
    return finished;
  }
  current_.push_back(sample);
  return finished;
}

void RevolutionAssembler::Reset() {
  dropped_samples_ += static_cast<int64_t>(current_.size());
  current_.clear();
  started_ = false;
  have_last_angle_ = false;
  covered_q6_ = 0;
  started_by_wrap_ = false;
}

}  // namespace rplidar
}  // namespace slammtt
