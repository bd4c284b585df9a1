// A valid sample of every message type with a variable-length array or a string, and where its
// counts and string lengths sit in the encoding, for the tests of runtime/message_checks.h.
//
// The offsets are derived here independently of the checks, field by field from lcmtypes/*.lcm
// (LCM type specification: 8-byte fingerprint, fields in declaration order, big-endian, a string
// as an int32 length counting the NUL followed by its bytes). The tests read the int32 at each
// offset back and expect the sample's count there, so a changed type shows up as a failed
// expectation naming the field rather than as a silently meaningless test.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/leg_labels_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/lidar_status_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/trajectory_t.hpp"
#include "slammtt_msgs/smoother_input_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"

namespace slammtt {
namespace testing_samples {

// An int32 of the encoding that announces how much follows: an array count or a string length.
struct CountField {
  std::string name;
  size_t offset = 0;    // of its first (most significant) byte
  int32_t value = 0;    // in the sample
};

inline int32_t StringLength(const std::string& s) { return static_cast<int32_t>(s.size()) + 1; }

// Appends the string length field at `*offset` and moves past the string.
inline void AddString(std::vector<CountField>* fields, const std::string& name,
                      const std::string& s, size_t* offset) {
  fields->push_back({name, *offset, StringLength(s)});
  *offset += 4 + s.size() + 1;
}

constexpr size_t kFingerprint = 8;

// The big-endian int32 at `offset` of an encoding (LCM's byte order), as a count field holds it.
inline int32_t ReadInt32(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t v = 0;
  for (size_t k = 0; k < 4; ++k) v = (v << 8) | bytes.at(offset + k);
  return static_cast<int32_t>(v);
}

// Overwrites the big-endian int32 at `offset`: how the tests damage a count or a length.
inline void WriteInt32(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  for (size_t k = 0; k < 4; ++k) {
    bytes->at(offset + k) = static_cast<uint8_t>(static_cast<uint32_t>(value) >> (24 - 8 * k));
  }
}

// Sample<Msg>::Make() builds a valid message with every array non-empty, distinct values and
// at least one empty string where the type has strings; Counts() lists its count fields;
// ArraysMatchCounts() is what a consumer relies on after a successful decode.
template <class Msg>
struct Sample;

template <>
struct Sample<slammtt_msgs::laser_scan_t> {
  static slammtt_msgs::laser_scan_t Make() {
    slammtt_msgs::laser_scan_t m{};
    m.utime = 1700000000123456;
    m.sequence = 17;
    m.scan_duration_us = 100000;
    m.range_min_m = 0.15f;
    m.range_max_m = 12.0f;
    m.num_beams = 5;
    for (int k = 0; k < m.num_beams; ++k) {
      m.angle_rad.push_back(-1.0f + 0.5f * static_cast<float>(k));
      m.range_m.push_back(1.0f + static_cast<float>(k));
      m.intensity.push_back(static_cast<float>(10 * k));
      m.valid.push_back(k % 2 == 0 ? 1 : 0);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::laser_scan_t& m) {
    // fingerprint, utime, sequence, scan_duration_us (int64), range_min_m, range_max_m (float)
    return {{"num_beams", kFingerprint + 3 * 8 + 2 * 4, m.num_beams}};
  }
  static bool ArraysMatchCounts(const slammtt_msgs::laser_scan_t& m) {
    const size_t n = static_cast<size_t>(m.num_beams);
    return m.num_beams >= 0 && m.angle_rad.size() == n && m.range_m.size() == n &&
           m.intensity.size() == n && m.valid.size() == n;
  }
};

template <>
struct Sample<slammtt_msgs::features_t> {
  static slammtt_msgs::features_t Make() {
    slammtt_msgs::features_t m{};
    m.utime = 1700000000200000;
    m.sequence = 3;
    m.num_features = 3;
    for (int k = 0; k < m.num_features; ++k) {
      slammtt_msgs::feature_t f{};
      f.range_m = 2.0 + k;
      f.bearing_rad = -0.3 * k;
      f.width_m = 0.1 * k;
      f.num_points = 4 + k;
      f.range_var_m2 = 0.0009;
      f.bearing_var_rad2 = 0.0012;
      f.range_bearing_cov_m_rad = 1e-5 * k;
      f.leg_likeness = 0.25 * k;
      m.features.push_back(f);
    }
    m.num_lines = 2;
    for (int k = 0; k < m.num_lines; ++k) {
      slammtt_msgs::line_feature_t l{};
      l.rho_m = 1.5 + k;
      l.alpha_rad = 0.4 - k;
      l.rho_var_m2 = 1e-4;
      l.alpha_var_rad2 = 2e-4;
      l.rho_alpha_cov_m_rad = -1e-6 * k;
      l.first_x_m = 1.0;
      l.first_y_m = -1.0 + k;
      l.last_x_m = 1.2;
      l.last_y_m = 1.0 + k;
      l.num_points = 40 + k;
      l.rms_residual_m = 0.01;
      m.lines.push_back(l);
    }
    m.num_people = 1;
    slammtt_msgs::person_feature_t p{};
    p.range_m = 2.5;
    p.bearing_rad = -0.15;
    p.range_var_m2 = 0.01;
    p.bearing_var_rad2 = 0.002;
    p.range_bearing_cov_m_rad = 0.0;
    p.num_legs = 2;
    p.leg_index[0] = 0;
    p.leg_index[1] = 1;
    p.confidence = 0.8;
    m.people.push_back(p);
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::features_t& m) {
    const size_t after_features = kFingerprint + 2 * 8 + 4 +  // utime, sequence, num_features
                                  static_cast<size_t>(m.num_features) * 60;
    const size_t after_lines = after_features + 4 + static_cast<size_t>(m.num_lines) * 84;
    return {{"num_features", kFingerprint + 2 * 8, m.num_features},
            {"num_lines", after_features, m.num_lines},
            {"num_people", after_lines, m.num_people}};
  }
  static bool ArraysMatchCounts(const slammtt_msgs::features_t& m) {
    return m.num_features >= 0 && m.features.size() == static_cast<size_t>(m.num_features) &&
           m.num_lines >= 0 && m.lines.size() == static_cast<size_t>(m.num_lines) &&
           m.num_people >= 0 && m.people.size() == static_cast<size_t>(m.num_people);
  }
};

template <>
struct Sample<slammtt_msgs::ground_truth_t> {
  static slammtt_msgs::ground_truth_t Make() {
    slammtt_msgs::ground_truth_t m{};
    m.utime = 1700000000300000;
    m.robot_x_m = 1.5;
    m.robot_y_m = -2.25;
    m.robot_heading_rad = 0.7;
    m.robot_linear_mps = 0.25;
    m.robot_angular_radps = -0.1;
    m.num_objects = 2;
    for (int k = 0; k < m.num_objects; ++k) {
      slammtt_msgs::object_truth_t o{};
      o.id = 100 + k;
      o.x_m = 3.0 * k;
      o.y_m = 1.0 - k;
      o.vx_mps = 0.625 * k;
      o.vy_mps = -0.75;
      o.radius_m = 0.3;
      o.object_class = static_cast<int8_t>(k);
      o.beams_on_object = 7 * k;
      o.visible = static_cast<int8_t>(k);
      o.kind = static_cast<int8_t>(k == 0 ? slammtt_msgs::object_truth_t::KIND_POST
                                          : slammtt_msgs::object_truth_t::KIND_PERSON);
      o.parent_id = -1;
      m.objects.push_back(o);
    }
    m.num_segments = 2;
    for (int k = 0; k < m.num_segments; ++k) {
      slammtt_msgs::segment_truth_t g{};
      g.id = 200 + k;
      g.kind = slammtt_msgs::segment_truth_t::KIND_WALL;
      g.x0_m = -1.0;
      g.y0_m = 2.0 * k;
      g.x1_m = 4.0;
      g.y1_m = 2.0 * k + 0.5;
      g.beams_on_segment = 30 + k;
      m.segments.push_back(g);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::ground_truth_t& m) {
    // after utime and the robot's x, y, heading, linear and angular velocity
    const size_t objects_at = kFingerprint + 8 + 5 * 8;
    return {{"num_objects", objects_at, m.num_objects},
            {"num_segments", objects_at + 4 + static_cast<size_t>(m.num_objects) * 63,
             m.num_segments}};
  }
  static bool ArraysMatchCounts(const slammtt_msgs::ground_truth_t& m) {
    return m.num_objects >= 0 && m.objects.size() == static_cast<size_t>(m.num_objects) &&
           m.num_segments >= 0 && m.segments.size() == static_cast<size_t>(m.num_segments);
  }
};

template <>
struct Sample<slammtt_msgs::tracks_t> {
  static slammtt_msgs::tracks_t Make() {
    slammtt_msgs::tracks_t m{};
    m.utime = 1700000000400000;
    m.num_tracks = 3;
    for (int k = 0; k < m.num_tracks; ++k) {
      slammtt_msgs::track_t t{};
      t.id = k + 1;
      t.x_m = 0.5 * k;
      t.y_m = -0.5 * k;
      t.vx_mps = 0.1 * k;
      t.vy_mps = 0.2;
      for (int i = 0; i < 16; ++i) t.covariance[i] = (i % 5 == 0) ? 0.04 : 0.001 * i;
      t.object_class = static_cast<int8_t>(k % 3);
      t.confirmed = static_cast<int8_t>(k > 0);
      t.first_seen_utime = 1700000000000000 + k;
      t.hits = 10 * k;
      t.last_seen_utime = 1700000000400000 - 100000 * k;
      t.measured = static_cast<int8_t>(k == 0);
      t.coasting_s = 0.1 * k;
      t.reported = static_cast<int8_t>(k == 1);
      t.kind = static_cast<int8_t>(k % 2);
      m.tracks.push_back(t);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::tracks_t& m) {
    return {{"num_tracks", kFingerprint + 8, m.num_tracks}};  // after utime
  }
  static bool ArraysMatchCounts(const slammtt_msgs::tracks_t& m) {
    return m.num_tracks >= 0 && m.tracks.size() == static_cast<size_t>(m.num_tracks);
  }
};

template <>
struct Sample<slammtt_msgs::map_t> {
  static slammtt_msgs::map_t Make() {
    slammtt_msgs::map_t m{};
    m.utime = 1700000000500000;
    m.num_landmarks = 4;
    for (int k = 0; k < m.num_landmarks; ++k) {
      slammtt_msgs::landmark_t l{};
      l.id = 10 + k;
      l.x_m = 5.0 - k;
      l.y_m = 2.0 * k;
      l.covariance[0] = 0.01;
      l.covariance[1] = 0.002 * k;
      l.covariance[2] = 0.002 * k;
      l.covariance[3] = 0.02;
      m.landmarks.push_back(l);
    }
    m.num_lines = 3;
    for (int k = 0; k < m.num_lines; ++k) {
      slammtt_msgs::line_landmark_t l{};
      l.id = 20 + k;
      l.rho_m = 1.5 * k - 1.0;
      l.alpha_rad = 0.4 * k;
      l.covariance[0] = 0.001;
      l.covariance[1] = 0.0001 * k;
      l.covariance[2] = 0.0001 * k;
      l.covariance[3] = 0.0004;
      l.from_x_m = k;
      l.from_y_m = 2.0;
      l.to_x_m = k + 1.5;
      l.to_y_m = -1.0;
      l.hits = 7 * k;
      m.lines.push_back(l);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::map_t& m) {
    // utime, num_landmarks, then the landmarks (id, x, y, covariance[4]).
    const size_t after_landmarks = kFingerprint + 8 + 4 + m.landmarks.size() * (8 + 6 * 8);
    return {{"num_landmarks", kFingerprint + 8, m.num_landmarks},
            {"num_lines", after_landmarks, m.num_lines}};
  }
  static bool ArraysMatchCounts(const slammtt_msgs::map_t& m) {
    return m.num_landmarks >= 0 && m.landmarks.size() == static_cast<size_t>(m.num_landmarks) &&
           m.num_lines >= 0 && m.lines.size() == static_cast<size_t>(m.num_lines);
  }
};

template <>
struct Sample<slammtt_msgs::stage_timing_t> {
  static slammtt_msgs::stage_timing_t Make() {
    slammtt_msgs::stage_timing_t m{};
    m.utime = 1700000000600000;
    m.stage = "estimator";
    m.total_ns = 123456;
    m.substage = {"predict", "gating", ""};
    m.substage_ns = {1000, 2000, 3};
    m.num_substages = 3;
    m.counter_name = {"hypotheses", "beams"};
    m.counter_value = {42, 720};
    m.num_counters = 2;
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::stage_timing_t& m) {
    std::vector<CountField> fields;
    size_t at = kFingerprint + 8;  // utime
    AddString(&fields, "stage", m.stage, &at);
    at += 8;  // total_ns
    fields.push_back({"num_substages", at, m.num_substages});
    at += 4;
    for (size_t k = 0; k < m.substage.size(); ++k) {
      AddString(&fields, "substage[" + std::to_string(k) + "]", m.substage[k], &at);
    }
    at += 8 * m.substage_ns.size();
    fields.push_back({"num_counters", at, m.num_counters});
    at += 4;
    for (size_t k = 0; k < m.counter_name.size(); ++k) {
      AddString(&fields, "counter_name[" + std::to_string(k) + "]", m.counter_name[k], &at);
    }
    return fields;
  }
  static bool ArraysMatchCounts(const slammtt_msgs::stage_timing_t& m) {
    return m.num_substages >= 0 && m.num_counters >= 0 &&
           m.substage.size() == static_cast<size_t>(m.num_substages) &&
           m.substage_ns.size() == static_cast<size_t>(m.num_substages) &&
           m.counter_name.size() == static_cast<size_t>(m.num_counters) &&
           m.counter_value.size() == static_cast<size_t>(m.num_counters);
  }
};

template <>
struct Sample<slammtt_msgs::lidar_status_t> {
  static slammtt_msgs::lidar_status_t Make() {
    slammtt_msgs::lidar_status_t m{};
    m.utime = 1700000000700000;
    m.connected = 1;
    m.state = "scanning";
    m.endpoint = "tcp://127.0.0.1:20108";
    m.model = 0x18;
    m.firmware_major = 1;
    m.firmware_minor = 29;
    m.hardware = 7;
    m.serial_number = "9C1AEDF2C1E392D4A5E59AF4B3513C0F";
    m.health = slammtt_msgs::lidar_status_t::HEALTH_GOOD;
    m.health_error_code = 0;
    m.scan_mode = "express";
    m.scan_rate_hz = 10.02;
    m.scans_published = 1234;
    m.nodes_decoded = 456789;
    m.resyncs = 2;
    m.checksum_errors = 1;
    m.reconnects = 0;
    m.last_error = "";
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::lidar_status_t& m) {
    std::vector<CountField> fields;
    size_t at = kFingerprint + 8 + 1;  // utime, connected
    AddString(&fields, "state", m.state, &at);
    AddString(&fields, "endpoint", m.endpoint, &at);
    at += 4 * 4;  // model, firmware_major, firmware_minor, hardware
    AddString(&fields, "serial_number", m.serial_number, &at);
    at += 1 + 4;  // health, health_error_code
    AddString(&fields, "scan_mode", m.scan_mode, &at);
    at += 8 + 5 * 8;  // scan_rate_hz, five counters
    AddString(&fields, "last_error", m.last_error, &at);
    return fields;
  }
  static bool ArraysMatchCounts(const slammtt_msgs::lidar_status_t&) { return true; }
};

template <>
struct Sample<slammtt_msgs::base_status_t> {
  static slammtt_msgs::base_status_t Make() {
    slammtt_msgs::base_status_t m{};
    m.utime = 1700000000800000;
    m.connected = 1;
    m.state = "running";
    m.endpoint = "/dev/ttyUSB0";
    m.robot_name = "MobileRobots";
    m.robot_class = "Pioneer";
    m.robot_subclass = "p3dx-sh";
    m.battery_v = 12.6;
    m.left_wheel_stall = 0;
    m.right_wheel_stall = 1;
    m.bumpers = 0x0102;
    m.motors_enabled = 1;
    m.command_timeout_stop = 0;
    m.sips_received = 5000;
    m.checksum_errors = 3;
    m.short_packets = 1;
    m.reconnects = 0;
    m.last_error = "";
    m.command_auth = "hmac-sha256";
    m.commands_accepted = 120;
    m.commands_unauthenticated = 40;
    m.commands_stale = 2;
    m.commands_replayed = 1;
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::base_status_t& m) {
    std::vector<CountField> fields;
    size_t at = kFingerprint + 8 + 1;  // utime, connected
    AddString(&fields, "state", m.state, &at);
    AddString(&fields, "endpoint", m.endpoint, &at);
    AddString(&fields, "robot_name", m.robot_name, &at);
    AddString(&fields, "robot_class", m.robot_class, &at);
    AddString(&fields, "robot_subclass", m.robot_subclass, &at);
    // battery_v, two stalls, bumpers, motors_enabled, command_timeout_stop, four counters
    at += 8 + 2 * 1 + 4 + 2 * 1 + 4 * 8;
    AddString(&fields, "last_error", m.last_error, &at);
    AddString(&fields, "command_auth", m.command_auth, &at);
    return fields;
  }
  static bool ArraysMatchCounts(const slammtt_msgs::base_status_t&) { return true; }
};

template <>
struct Sample<slammtt_msgs::estimator_status_t> {
  static slammtt_msgs::estimator_status_t Make() {
    slammtt_msgs::estimator_status_t m{};
    m.utime = 1700000000900000;
    m.scans_processed = 80;
    m.odometry_processed = 400;
    m.features_rejected = 2;
    m.messages_out_of_order = 1;
    m.time_gaps = 0;
    m.scans_without_odometry = 1;
    m.object_cap_hits = 0;
    m.hypotheses_generated = 9000;
    m.num_landmarks = 6;
    m.num_moving = 5;
    m.num_tentative = 1;
    m.last_event = "odometry older than the last processed scan dropped";
    m.odometry_rejected = 3;
    m.messages_undecodable = 4;
    m.updates_failed = 5;
    m.heading_drift_rad_per_m = -0.0009;
    m.heading_drift_sigma_rad_per_m = 0.002;
    m.restarts = 1;
    m.time_jumps_rejected = 2;
    m.odometry_frame_jumps = 1;
    m.state_recoveries = 0;
    m.features_over_cap = 7;
    m.ransac_budget_cuts = 1;
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::estimator_status_t& m) {
    std::vector<CountField> fields;
    size_t at = kFingerprint + 9 * 8 + 3 * 4;  // utime and eight counters, three sizes
    AddString(&fields, "last_event", m.last_event, &at);
    return fields;
  }
  static bool ArraysMatchCounts(const slammtt_msgs::estimator_status_t&) { return true; }
};

template <>
struct Sample<slammtt_msgs::leg_labels_t> {
  static slammtt_msgs::leg_labels_t Make() {
    slammtt_msgs::leg_labels_t m{};
    m.utime = 1700000001000000;
    m.num_legs = 3;
    for (int k = 0; k < m.num_legs; ++k) {
      m.x_m.push_back(1.0 + 0.5 * k);
      m.y_m.push_back(-0.25 * k);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::leg_labels_t& m) {
    return {{"num_legs", kFingerprint + 8, m.num_legs}};  // after utime
  }
  static bool ArraysMatchCounts(const slammtt_msgs::leg_labels_t& m) {
    const size_t n = static_cast<size_t>(m.num_legs);
    return m.num_legs >= 0 && m.x_m.size() == n && m.y_m.size() == n;
  }
};

template <>
struct Sample<slammtt_msgs::laser_geometry_t> {
  static slammtt_msgs::laser_geometry_t Make() {
    slammtt_msgs::laser_geometry_t m{};
    m.utime = 1700000000900000;
    m.mount_forward_m = 0.1;
    m.mount_left_m = -0.02;
    m.mount_yaw_rad = 0.5;
    m.view_start_rad = -M_PI / 2;
    m.view_end_rad = M_PI / 2;
    m.range_min_m = 0.1;
    m.range_max_m = 30.0;
    m.source = "slammtt-world, scenario s2-lobby";
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::laser_geometry_t& m) {
    std::vector<CountField> fields;
    size_t at = kFingerprint + 8 + 7 * 8;  // utime, seven doubles
    AddString(&fields, "source", m.source, &at);
    return fields;
  }
  static bool ArraysMatchCounts(const slammtt_msgs::laser_geometry_t&) { return true; }
};

template <>
struct Sample<slammtt_msgs::smoother_input_t> {
  static slammtt_msgs::smoother_input_t Make() {
    slammtt_msgs::smoother_input_t m{};
    m.utime = 1700000001000000;
    m.x_m = 1.5;
    m.y_m = -0.5;
    m.heading_rad = 0.3;
    for (int k = 0; k < 9; k += 4) m.pose_covariance[k] = 0.01;
    m.continues = true;
    m.dx_m = 0.1;
    m.dtheta_rad = 0.02;
    for (int k = 0; k < 9; k += 4) m.increment_covariance[k] = 0.001;
    m.sensor_forward_m = 0.1;
    m.num_observations = 3;
    for (int k = 0; k < m.num_observations; ++k) {
      slammtt_msgs::smoother_observation_t o{};
      o.landmark_id = 40 + k;
      o.range_m = 2.0 + k;
      o.bearing_rad = 0.2 * k - 0.2;
      o.covariance[0] = 0.04;
      o.covariance[3] = 0.001;
      o.tentative = k == 2;
      m.observations.push_back(o);
    }
    m.num_removed = 2;
    m.removed_landmark_ids = {7, 9};
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::smoother_input_t& m) {
    // utime, 12 doubles, continues, 12 doubles, 3 doubles; then the observations (landmark_id,
    // range, bearing, covariance[4], tentative).
    const size_t observations_at = kFingerprint + 8 + 12 * 8 + 1 + 12 * 8 + 3 * 8;
    const size_t removed_at = observations_at + 4 + m.observations.size() * (8 + 6 * 8 + 1);
    return {{"num_observations", observations_at, m.num_observations},
            {"num_removed", removed_at, m.num_removed}};
  }
  static bool ArraysMatchCounts(const slammtt_msgs::smoother_input_t& m) {
    return m.num_observations >= 0 &&
           m.observations.size() == static_cast<size_t>(m.num_observations) &&
           m.num_removed >= 0 && m.removed_landmark_ids.size() == static_cast<size_t>(m.num_removed);
  }
};

template <>
struct Sample<slammtt_msgs::trajectory_t> {
  static slammtt_msgs::trajectory_t Make() {
    slammtt_msgs::trajectory_t m{};
    m.utime = 1700000002000000;
    m.num_poses = 3;
    for (int k = 0; k < m.num_poses; ++k) {
      m.pose_utime.push_back(1700000000000000 + 125000 * k);
      m.x_m.push_back(0.5 * k);
      m.y_m.push_back(-0.1 * k);
      m.heading_rad.push_back(0.05 * k);
    }
    return m;
  }
  static std::vector<CountField> Counts(const slammtt_msgs::trajectory_t& m) {
    return {{"num_poses", kFingerprint + 8, m.num_poses}};  // after utime
  }
  static bool ArraysMatchCounts(const slammtt_msgs::trajectory_t& m) {
    const size_t n = static_cast<size_t>(m.num_poses);
    return m.num_poses >= 0 && m.pose_utime.size() == n && m.x_m.size() == n &&
           m.y_m.size() == n && m.heading_rad.size() == n;
  }
};

// Every type with a Sample above, for the typed tests of the checks and of the fuzzer: a new
// type is added here once.
using SampledTypes =
    ::testing::Types<slammtt_msgs::laser_scan_t, slammtt_msgs::features_t,
                     slammtt_msgs::ground_truth_t, slammtt_msgs::tracks_t, slammtt_msgs::map_t,
                     slammtt_msgs::stage_timing_t, slammtt_msgs::lidar_status_t,
                     slammtt_msgs::base_status_t, slammtt_msgs::estimator_status_t,
                     slammtt_msgs::leg_labels_t, slammtt_msgs::laser_geometry_t,
                     slammtt_msgs::smoother_input_t, slammtt_msgs::trajectory_t>;

// Names each typed test after its message type ("laser_scan_t") instead of a number.
class SampledTypeNames {
 public:
  template <class Msg>
  static std::string GetName(int) {
    return Msg::getTypeName();
  }
};

}  // namespace testing_samples
}  // namespace slammtt
