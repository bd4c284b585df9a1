// Structural checks of encoded LCM messages, run by slammtt::Decode (runtime/lcm_io.h) before
// LCM's generated decoder ever sees the bytes.
//
// Why: LCM 1.3.1's generated C++ decoders (`_decodeNoHash` in the headers lcm-gen writes from
// lcmtypes/*.lcm) resize every variable-length array to the count the message CLAIMS before they
// check that the bytes are there, and a string of claimed length L is assigned L - 1 characters.
// A corrupt count or length from the bus therefore throws std::length_error (negative),
// allocates and zeroes gigabytes (large: one corrupt FEATURES count cost the estimator 7.7 s and
// 2.7 GB in replay), or, when 4 * count overflows int (float and int32 arrays), passes the
// decoder's own bound check and reads past the buffer (seen: SIGSEGV in __int32_t_decode_array
// on a damaged laser_scan_t). Bus input is untrusted; these checks keep the decoder's reads
// inside the message and its allocations bounded by the message's own size.
//
// The encoding walked here (LCM type specification,
// https://lcm-proj.github.io/lcm/content/lcm-type-ref.html, and /usr/include/lcm/lcm_coretypes.h):
// - an 8-byte fingerprint (the type's hash), then every field in declaration order, big-endian,
//   with no padding; a nested struct (feature_t inside features_t, ...) has no fingerprint;
// - int8_t and boolean 1 byte, int32_t and float 4, int64_t and double 8;
// - a string: int32 length counting the terminating NUL, then that many bytes, the last a NUL;
// - an array `T a[n]`: its n elements one after another, n being an earlier int32 field; arrays
//   sharing one count are encoded one whole array after the other (laser_scan_t: all angles,
//   then all ranges, ...); a fixed-size array `double c[16]` is 16 doubles.
//
// Each Plausible<Type>() walks the whole encoding of its type and returns true only when
// - every string length is >= 1, fits in the bytes that remain and its last byte is the NUL,
// - every array count is >= 0 and its elements at their smallest encoded size fit in the bytes
//   that remain (checked before any element is walked, so a huge count costs O(1)),
// - the walk ends exactly at `size`.
// The checks never allocate and never throw; their cost grows with the number of strings only
// (arrays of fixed-size elements are skipped whole). True does not mean the fingerprint matches
// (the generated decoder checks it) nor that the values make sense (each consumer checks them).
// A null `data` or a negative `size` is false.
#pragma once

#include <cstdint>

#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/leg_labels_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/lidar_status_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/smoother_input_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "slammtt_msgs/trajectory_t.hpp"

namespace slammtt {

// Encoded sizes in bytes, as the LCM type specification gives them, of what the checks skip.
// Each fixed-size element is its fields' sizes summed in declaration order (lcmtypes/*.lcm);
// tests/runtime/message_checks_test.cc compares them with lcm-gen's own sizes.
namespace encoded_bytes {
inline constexpr int64_t kFingerprint = 8;
inline constexpr int64_t kInt8 = 1;
inline constexpr int64_t kBoolean = 1;
inline constexpr int64_t kInt32 = 4;
inline constexpr int64_t kFloat = 4;
inline constexpr int64_t kInt64 = 8;
inline constexpr int64_t kDouble = 8;
// The shortest string: its length field and the NUL.
inline constexpr int64_t kEmptyString = kInt32 + 1;
// One laser_scan_t beam: angle_rad, range_m, intensity (floats) and valid (boolean).
inline constexpr int64_t kBeam = 3 * kFloat + kBoolean;
// feature_t: range_m, bearing_rad, width_m, num_points, range_var_m2, bearing_var_rad2,
// range_bearing_cov_m_rad, leg_likeness.
inline constexpr int64_t kFeature = 3 * kDouble + kInt32 + 4 * kDouble;
// line_feature_t: rho_m, alpha_rad, rho_var_m2, alpha_var_rad2, rho_alpha_cov_m_rad, first_x_m,
// first_y_m, last_x_m, last_y_m, num_points, rms_residual_m.
inline constexpr int64_t kLineFeature = 9 * kDouble + kInt32 + kDouble;
// person_feature_t: range_m, bearing_rad, range_var_m2, bearing_var_rad2,
// range_bearing_cov_m_rad, num_legs, leg_index[2], confidence.
inline constexpr int64_t kPersonFeature = 5 * kDouble + kInt32 + 2 * kInt32 + kDouble;
// object_truth_t: id, x_m, y_m, vx_mps, vy_mps, radius_m, object_class, beams_on_object, visible,
// kind, parent_id.
inline constexpr int64_t kObjectTruth =
    kInt64 + 5 * kDouble + kInt8 + kInt32 + kBoolean + kInt8 + kInt64;
// segment_truth_t: id, kind, x0_m, y0_m, x1_m, y1_m, beams_on_segment.
inline constexpr int64_t kSegmentTruth = kInt64 + kInt8 + 4 * kDouble + kInt32;
// One leg_labels_t label: x_m and y_m.
inline constexpr int64_t kLegLabel = 2 * kDouble;
// One trajectory_t pose: pose_utime, x_m, y_m, heading_rad.
inline constexpr int64_t kTrajectoryPose = kInt64 + 3 * kDouble;
// track_t: id, x_m, y_m, vx_mps, vy_mps, covariance[16], object_class, confirmed,
// first_seen_utime, hits, last_seen_utime, measured, coasting_s, reported, kind.
inline constexpr int64_t kTrack = kInt64 + 4 * kDouble + 16 * kDouble + kInt8 + kBoolean +
                                  kInt64 + kInt32 + kInt64 + kBoolean + kDouble + kBoolean + kInt8;
// landmark_t: id, x_m, y_m, covariance[4].
inline constexpr int64_t kLandmark = kInt64 + 2 * kDouble + 4 * kDouble;
// line_landmark_t: id, rho_m, alpha_rad, covariance[4], from_x_m, from_y_m, to_x_m, to_y_m,
// hits.
inline constexpr int64_t kLineLandmark =
    kInt64 + 2 * kDouble + 4 * kDouble + 4 * kDouble + kInt32;
// smoother_observation_t: landmark_id, range_m, bearing_rad, covariance[4], tentative.
inline constexpr int64_t kSmootherObservation = kInt64 + 2 * kDouble + 4 * kDouble + kBoolean;
}  // namespace encoded_bytes

// One function per type of lcmtypes/ with a variable-length array or a string; see above.
bool PlausibleLaserScan(const void* data, int size);
bool PlausibleFeatures(const void* data, int size);
bool PlausibleGroundTruth(const void* data, int size);
bool PlausibleTracks(const void* data, int size);
bool PlausibleMap(const void* data, int size);
bool PlausibleStageTiming(const void* data, int size);
bool PlausibleLidarStatus(const void* data, int size);
bool PlausibleBaseStatus(const void* data, int size);
bool PlausibleEstimatorStatus(const void* data, int size);
bool PlausibleLegLabels(const void* data, int size);
bool PlausibleLaserGeometry(const void* data, int size);
bool PlausibleSmootherInput(const void* data, int size);
bool PlausibleTrajectory(const void* data, int size);

// The check of a type, chosen by overload on a (never dereferenced) pointer to the type.
inline bool PlausibleEncoding(const slammtt_msgs::laser_scan_t*, const void* data, int size) {
  return PlausibleLaserScan(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::features_t*, const void* data, int size) {
  return PlausibleFeatures(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::ground_truth_t*, const void* data, int size) {
  return PlausibleGroundTruth(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::tracks_t*, const void* data, int size) {
  return PlausibleTracks(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::map_t*, const void* data, int size) {
  return PlausibleMap(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::stage_timing_t*, const void* data, int size) {
  return PlausibleStageTiming(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::lidar_status_t*, const void* data, int size) {
  return PlausibleLidarStatus(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::base_status_t*, const void* data, int size) {
  return PlausibleBaseStatus(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::estimator_status_t*, const void* data,
                              int size) {
  return PlausibleEstimatorStatus(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::leg_labels_t*, const void* data, int size) {
  return PlausibleLegLabels(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::laser_geometry_t*, const void* data,
                              int size) {
  return PlausibleLaserGeometry(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::smoother_input_t*, const void* data,
                              int size) {
  return PlausibleSmootherInput(data, size);
}
inline bool PlausibleEncoding(const slammtt_msgs::trajectory_t*, const void* data, int size) {
  return PlausibleTrajectory(data, size);
}
// Every other type (odometry_t, pose_t, velocity_command_t and the nested element types) has a
// fixed size: the generated decoder checks each read against `size` before it makes it and
// allocates nothing, so there is nothing to check first. A new type with an array or a string
// needs its own overload above: tests/runtime/message_checks_test.cc reads lcmtypes/*.lcm and
// fails until it has one.
inline bool PlausibleEncoding(const void*, const void* data, int size) {
  return data != nullptr && size >= 0;
}

}  // namespace slammtt
