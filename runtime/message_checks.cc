#include "runtime/message_checks.h"

namespace slammtt {
namespace {

using namespace encoded_bytes;  // NOLINT(build/namespaces): the sizes read as a layout table

// Walks an encoded LCM message from its first byte. The first failed step marks the walk bad;
// every later step is then a no-op, so a check reads as the type's field list.
class EncodedWalk {
 public:
  EncodedWalk(const void* data, int size)
      : bytes_(static_cast<const uint8_t*>(data)), size_(size), ok_(data != nullptr && size >= 0) {}

  // Fields of a fixed total size.
  void Fixed(int64_t bytes) {
    if (!ok_ || bytes > Remaining()) {
      ok_ = false;
      return;
    }
    position_ += bytes;
  }

  // An array count, accepted when `count` elements of at least `min_element_bytes` each fit in
  // what remains; 0 when the walk is (or becomes) bad.
  int32_t Count(int64_t min_element_bytes) {
    const int32_t count = Int32();
    if (!ok_ || count < 0 || count * min_element_bytes > Remaining()) {
      ok_ = false;
      return 0;
    }
    return count;
  }

  // `count` elements of exactly `element_bytes` each (the count was checked by Count()).
  void Elements(int32_t count, int64_t element_bytes) { Fixed(count * element_bytes); }

  // One string: length >= 1 including the NUL, within what remains, and NUL-terminated.
  void String() {
    const int32_t length = Int32();
    if (!ok_ || length < 1 || length > Remaining() || bytes_[position_ + length - 1] != 0) {
      ok_ = false;
      return;
    }
    position_ += length;
  }

  void Strings(int32_t count) {
    for (int32_t k = 0; k < count && ok_; ++k) String();
  }

  // The walk covered the whole message and nothing more.
  bool End() const { return ok_ && position_ == size_; }

 private:
  int64_t Remaining() const { return size_ - position_; }

  int32_t Int32() {
    if (!ok_ || Remaining() < kInt32) {
      ok_ = false;
      return 0;
    }
    uint32_t value = 0;
    for (int k = 0; k < 4; ++k) value = (value << 8) | bytes_[position_ + k];
    position_ += kInt32;
    return static_cast<int32_t>(value);
  }

  const uint8_t* bytes_;
  int64_t size_;
  int64_t position_ = 0;
  bool ok_;
};

}  // namespace

bool PlausibleLaserScan(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + 3 * kInt64 + 2 * kFloat);  // utime, sequence, scan_duration_us, ranges
  const int32_t beams = w.Count(kBeam);              // num_beams
  w.Elements(beams, kBeam);  // angle_rad[], range_m[], intensity[], valid[]
  return w.End();
}

bool PlausibleFeatures(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + 2 * kInt64);  // utime, sequence
  const int32_t features = w.Count(kFeature);
  w.Elements(features, kFeature);
  const int32_t lines = w.Count(kLineFeature);
  w.Elements(lines, kLineFeature);
  const int32_t people = w.Count(kPersonFeature);
  w.Elements(people, kPersonFeature);
  return w.End();
}

bool PlausibleGroundTruth(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64 + 5 * kDouble);  // utime, robot x, y, heading, linear, angular
  const int32_t objects = w.Count(kObjectTruth);
  w.Elements(objects, kObjectTruth);
  const int32_t segments = w.Count(kSegmentTruth);
  w.Elements(segments, kSegmentTruth);
  return w.End();
}

bool PlausibleLegLabels(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64);  // utime
  const int32_t legs = w.Count(kLegLabel);
  w.Elements(legs, kLegLabel);  // x_m[], y_m[]
  return w.End();
}

bool PlausibleTrajectory(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64);  // utime
  const int32_t poses = w.Count(kTrajectoryPose);
  w.Elements(poses, kTrajectoryPose);  // pose_utime[], x_m[], y_m[], heading_rad[]
  return w.End();
}

bool PlausibleTracks(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64);  // utime
  const int32_t tracks = w.Count(kTrack);
  w.Elements(tracks, kTrack);
  return w.End();
}

bool PlausibleMap(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64);  // utime
  const int32_t landmarks = w.Count(kLandmark);
  w.Elements(landmarks, kLandmark);
  const int32_t lines = w.Count(kLineLandmark);
  w.Elements(lines, kLineLandmark);
  return w.End();
}

bool PlausibleStageTiming(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64);  // utime
  w.String();                      // stage
  w.Fixed(kInt64);                 // total_ns
  // Each sub-stage and each counter: a name (at least its length and the NUL) and an int64.
  const int32_t substages = w.Count(kEmptyString + kInt64);
  w.Strings(substages);               // substage[]
  w.Elements(substages, kInt64);      // substage_ns[]
  const int32_t counters = w.Count(kEmptyString + kInt64);
  w.Strings(counters);                // counter_name[]
  w.Elements(counters, kInt64);       // counter_value[]
  return w.End();
}

bool PlausibleLidarStatus(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64 + kBoolean);  // utime, connected
  w.String();                                 // state
  w.String();                                 // endpoint
  w.Fixed(4 * kInt32);                        // model, firmware_major/minor, hardware
  w.String();                                 // serial_number
  w.Fixed(kInt8 + kInt32);                    // health, health_error_code
  w.String();                                 // scan_mode
  // scan_rate_hz, scans_published, nodes_decoded, resyncs, checksum_errors, reconnects
  w.Fixed(kDouble + 5 * kInt64);
  w.String();  // last_error
  return w.End();
}

bool PlausibleBaseStatus(const void* data, int size) {
  EncodedWalk w(data, size);
  w.Fixed(kFingerprint + kInt64 + kBoolean);  // utime, connected
  w.Strings(5);  // state, endpoint, robot_name, robot_class, robot_subclass
  // battery_v, left/right_wheel_stall, bumpers, motors_enabled, command_timeout_stop,
  // sips_received, checksum_errors, short_packets, reconnects
  w.Fixed(kDouble + 2 * kBoolean + kInt32 + 2 * kBoolean + 4 * kInt64);
  w.String();  // last_error
  w.String();  // command_auth
  // commands_accepted, commands_unauthenticated, commands_stale, commands_replayed
  w.Fixed(4 * kInt64);
  return w.End();
}

bool PlausibleLaserGeometry(const void* data, int size) {
  EncodedWalk w(data, size);
  // utime; mount forward, left, yaw; view start, end; range min, max
  w.Fixed(kFingerprint + kInt64 + 7 * kDouble);
  w.String();  // source
  return w.End();
}

bool PlausibleSmootherInput(const void* data, int size) {
  EncodedWalk w(data, size);
  // utime; x, y, heading, pose_covariance[9]; continues; dx, dy, dtheta,
  // increment_covariance[9]; sensor forward, left, yaw
  w.Fixed(kFingerprint + kInt64 + 12 * kDouble + kBoolean + 12 * kDouble + 3 * kDouble);
  const int32_t observations = w.Count(kSmootherObservation);
  w.Elements(observations, kSmootherObservation);
  const int32_t removed = w.Count(kInt64);
  w.Elements(removed, kInt64);  // removed_landmark_ids[]
  return w.End();
}

bool PlausibleEstimatorStatus(const void* data, int size) {
  EncodedWalk w(data, size);
  // utime, scans/odometry processed, features_rejected, messages_out_of_order, time_gaps,
  // scans_without_odometry, object_cap_hits, hypotheses_generated; num_landmarks/moving/tentative
  w.Fixed(kFingerprint + 9 * kInt64 + 3 * kInt32);
  w.String();  // last_event
  w.Fixed(3 * kInt64);  // odometry_rejected, messages_undecodable, updates_failed
  w.Fixed(2 * kDouble);  // heading_drift_rad_per_m, heading_drift_sigma_rad_per_m
  // restarts, time_jumps_rejected, odometry_frame_jumps, state_recoveries, features_over_cap,
  // ransac_budget_cuts
  w.Fixed(6 * kInt64);
  return w.End();
}

}  // namespace slammtt
