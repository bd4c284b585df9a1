#include "tools/replay/message_checks.h"

#include <cstdint>

namespace slammtt {
namespace {

// Reads big-endian fields of an encoded LCM message; any read past the end marks it bad.
class EncodedReader {
 public:
  EncodedReader(const void* data, int size)
      : bytes_(static_cast<const uint8_t*>(data)), size_(size) {}
  bool ok() const { return ok_; }
  int64_t remaining() const { return ok_ ? size_ - position_ : 0; }
  void Skip(int64_t n) {
    if (n < 0 || n > remaining()) {
      ok_ = false;
      return;
    }
    position_ += n;
  }
  int32_t Int32() {
    if (remaining() < 4) {
      ok_ = false;
      return 0;
    }
    uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v = (v << 8) | bytes_[position_ + k];
    position_ += 4;
    return static_cast<int32_t>(v);
  }
  void SkipString() {
    const int32_t length = Int32();  // including the terminating NUL
    if (length < 1) ok_ = false;
    Skip(length);
  }
  // An array length whose `count` elements of at least `min_bytes` each fit in what remains.
  bool Count(int32_t count, int64_t min_bytes) {
    if (!ok_ || count < 0 || static_cast<int64_t>(count) * min_bytes > remaining()) ok_ = false;
    return ok_;
  }

 private:
  const uint8_t* bytes_;
  int64_t size_;
  int64_t position_ = 0;
  bool ok_ = true;
};

constexpr int64_t kFingerprint = 8;

}  // namespace

bool PlausibleGroundTruth(const void* data, int size) {
  EncodedReader r(data, size);
  r.Skip(kFingerprint + 8 + 5 * 8);  // utime, robot x, y, heading, linear, angular
  // object_truth_t: id, x, y, vx, vy, radius, class (int8), beams (int32), visible (boolean)
  return r.Count(r.Int32(), 8 + 5 * 8 + 1 + 4 + 1);
}

bool PlausibleTracks(const void* data, int size) {
  EncodedReader r(data, size);
  r.Skip(kFingerprint + 8);  // utime
  // track_t: id, x, y, vx, vy, covariance[16], class, confirmed, first_seen, hits, last_seen
  return r.Count(r.Int32(), 8 + 4 * 8 + 16 * 8 + 1 + 1 + 8 + 4 + 8);
}

bool PlausibleMap(const void* data, int size) {
  EncodedReader r(data, size);
  r.Skip(kFingerprint + 8);  // utime
  // landmark_t: id, x, y, covariance[4]
  return r.Count(r.Int32(), 8 + 2 * 8 + 4 * 8);
}

bool PlausibleStageTiming(const void* data, int size) {
  EncodedReader r(data, size);
  r.Skip(kFingerprint + 8);  // utime
  r.SkipString();            // stage
  r.Skip(8);                 // total_ns
  const int32_t substages = r.Int32();
  // Each sub-stage: a name (length + at least the NUL) and a duration.
  if (!r.Count(substages, 4 + 1 + 8)) return false;
  for (int32_t k = 0; k < substages && r.ok(); ++k) r.SkipString();
  r.Skip(static_cast<int64_t>(substages) * 8);
  const int32_t counters = r.Int32();
  return r.Count(counters, 4 + 1 + 8);
}

}  // namespace slammtt
