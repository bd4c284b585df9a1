// A hand-built log of five scans for the evaluation tests; every figure it should give is
// computed by hand in eval_test.cc.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"

namespace slammtt::testing {

constexpr int64_t kT0 = 1000000;
constexpr int64_t kScanUs = 125000;
constexpr int kScans = 5;
using Obj = slammtt_msgs::object_truth_t;
using Trk = slammtt_msgs::track_t;

inline int64_t ScanTime(int k) { return kT0 + k * kScanUs; }

// The estimator's map frame: truth point (X, Y) = (2 + py, 3 - px) for a map point (px, py),
// i.e. the map frame sits at (2, 3) turned by -90 degrees in the truth frame.
inline Eigen::Vector2d ToMap(double x, double y) { return Eigen::Vector2d(3.0 - y, x - 2.0); }

inline Obj Object(int64_t id, double x, double y, bool moving, bool visible, double vx = 0.0,
                  double vy = 0.0) {
  Obj o{};
  o.id = id;
  o.x_m = x;
  o.y_m = y;
  o.vx_mps = vx;
  o.vy_mps = vy;
  o.radius_m = 0.25;
  o.object_class = moving ? Obj::CLASS_MOVING : Obj::CLASS_STATIC;
  o.beams_on_object = visible ? 5 : 0;
  o.visible = visible;
  return o;
}

inline Trk Track(int64_t id, double truth_x, double truth_y, int8_t cls, bool confirmed = true) {
  Trk t{};
  t.id = id;
  const Eigen::Vector2d p = ToMap(truth_x, truth_y);
  t.x_m = p.x();
  t.y_m = p.y();
  t.covariance[0] = t.covariance[5] = 0.04;
  t.object_class = cls;
  t.confirmed = confirmed;
  t.reported = confirmed;  // measured in this scan
  t.measured = true;
  t.hits = 3;
  return t;
}

// Truth (5 scans): the robot drives along +x from (2, 3); static S1 (5, 5) always visible, S2
// (10, -5) visible at scan 0 only, S3 (20, 20) never; mover M1 walks (2 + k, 6), always visible;
// mover M2 walks (8, k), invisible at scan 2. The movers walk 1 m per scan: 8 m/s.
// Estimator: POSE exact but for 0.3 m at scan 3 and +0.1 rad at scan 4. Tracks: M1 by 100
// (0.3 m off) then by 102 at scan 4 (an identity switch); M2 by 101 except scan 3 (a miss, and
// a fragmentation when 101 returns at scan 4), 101 coasting on the invisible M2 at scan 2 (don't
// care); S1 by 200, undecided at scan 0 then static; an unconfirmed track (ignored); a false
// moving track 400 at scan 3.
// Odometry at 8 Hz, half a scan out of phase, in the base's frame, drifting 0.2 m in y per scan.
inline void WriteHandBuiltLog(const std::string& path, bool with_estimator) {
  LogWriter log(path);
  for (int k = 0; k <= kScans; ++k) {
    slammtt_msgs::odometry_t odo{};
    odo.utime = kT0 - kScanUs / 2 + k * kScanUs;
    odo.sequence = k;
    const double s = static_cast<double>(odo.utime - kT0) / kScanUs;  // scans since the first
    odo.x_m = s;
    odo.y_m = 0.2 * s;
    log.WriteMessage(odo.utime, "ODOMETRY", odo);
  }
  for (int k = 0; k < kScans; ++k) {
    const int64_t t = ScanTime(k);
    slammtt_msgs::ground_truth_t gt{};
    gt.utime = t;
    gt.robot_x_m = 2.0 + k;
    gt.robot_y_m = 3.0;
    gt.robot_linear_mps = 8.0;
    gt.objects = {Object(1, 5, 5, false, true), Object(2, 10, -5, false, k == 0),
                  Object(3, 20, 20, false, false), Object(10, 2.0 + k, 6, true, true, 8.0, 0.0),
                  Object(11, 8, k, true, k != 2, 0.0, 8.0)};
    gt.num_objects = static_cast<int32_t>(gt.objects.size());
    log.WriteMessage(t, "GROUND_TRUTH", gt);
    if (!with_estimator) continue;

    slammtt_msgs::pose_t pose{};
    pose.utime = t;
    pose.x_m = k == 3 ? 0.3 : 0.0;
    pose.y_m = k;
    pose.heading_rad = M_PI / 2 + (k == 4 ? 0.1 : 0.0);
    log.WriteMessage(t, "POSE", pose);

    slammtt_msgs::tracks_t tracks{};
    tracks.utime = t;
    tracks.tracks.push_back(Track(k == 4 ? 102 : 100, 2.0 + k, 6.3, Trk::CLASS_MOVING));
    if (k != 3) tracks.tracks.push_back(Track(101, 8, k, Trk::CLASS_MOVING));
    tracks.tracks.push_back(
        Track(200, 5, 5, k == 0 ? Trk::CLASS_UNDECIDED : Trk::CLASS_STATIC));
    tracks.tracks.push_back(Track(300, 15, 15, Trk::CLASS_MOVING, false));
    if (k == 3) tracks.tracks.push_back(Track(400, 30, 30, Trk::CLASS_MOVING));
    tracks.num_tracks = static_cast<int32_t>(tracks.tracks.size());
    log.WriteMessage(t, "TRACKS", tracks);
  }
  if (with_estimator) {
    slammtt_msgs::map_t map{};
    map.utime = ScanTime(kScans - 1);
    const std::vector<std::pair<int64_t, Eigen::Vector2d>> landmarks = {
        {1001, Eigen::Vector2d(5.1, 5)},     // S1, 0.1 m off
        {1002, Eigen::Vector2d(10, -4.8)},   // S2, 0.2 m off
        {1003, Eigen::Vector2d(4, 6.5)},     // 0.5 m beside M1's path
        {1004, Eigen::Vector2d(50, 50)}};    // nothing
    for (const auto& [id, truth] : landmarks) {
      slammtt_msgs::landmark_t l{};
      l.id = id;
      const Eigen::Vector2d p = ToMap(truth.x(), truth.y());
      l.x_m = p.x();
      l.y_m = p.y();
      l.covariance[0] = 0.09;
      l.covariance[3] = 0.01;
      map.landmarks.push_back(l);
    }
    map.num_landmarks = static_cast<int32_t>(map.landmarks.size());
    log.WriteMessage(map.utime, "MAP", map);
    // A broken pose (NaN) is rejected and counted, never used.
    slammtt_msgs::pose_t bad{};
    bad.utime = ScanTime(kScans + 3);
    bad.x_m = std::numeric_limits<double>::quiet_NaN();
    log.WriteMessage(bad.utime, "POSE", bad);
  }
  log.Commit();
}

}  // namespace slammtt::testing
