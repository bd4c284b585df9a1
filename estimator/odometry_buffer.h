// The odometry between two scans (paper eq. 1's inputs): the readings received since the
// previous scan, and the robot's motion they give up to the next scan.
//
// The base integrates its own pose in its own (drifting) odometry frame; the estimator uses only
// differences of consecutive integrated poses (eq.-1 increments, robot_motion_model.h). The
// buffer keeps a cursor (the odometry pose, time and velocities where the previous scan left
// the robot) and the readings newer than it, oldest first. For the motion to a scan at utime:
//  - every reading at or before utime is one increment, with the odometry's noise model;
//  - a reading after utime gives the part of its increment up to the scan, interpolated in
//    time (the cursor then sits at the scan, inside that increment);
//  - with no reading after the scan yet, the motion is extrapolated with the last velocities
//    over at most `max_s` seconds, with extra noise growing with the extrapolated time.
// Readings arrive in time order (the estimator drops older ones before they get here).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>

#include "estimator/ekf_prediction.h"
#include "estimator/robot_motion_model.h"

namespace slammtt {

// One odometry_t as the estimator needs it: the base's integrated pose in its own (drifting)
// odometry frame and its velocities.
struct OdometryReading {
  int64_t utime = 0;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // x_m, y_m, heading_rad
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

// Noise of motion extrapolated past the last reading, besides the odometry's own model: the
// variance of the distance grows by speed_var_per_s2 * tau^2 and that of the rotation by
// turn_var_per_s2 * tau^2 after tau seconds of extrapolation; tau is at most max_s.
struct ExtrapolationNoise {
  double speed_var_per_s2 = 0.0;  // [m^2/s^2]
  double turn_var_per_s2 = 0.0;   // [rad^2/s^2]
  double max_s = 0.0;
};

class OdometryBuffer {
 public:
  // Takes one reading (finite and newer than the previous one: the caller checks). The first
  // reading anchors the odometry: motion is measured from there on. A reading not newer than
  // the cursor (older than the last scan) only refreshes the velocities used to extrapolate.
  // The heading is wrapped to (-pi, pi].
  void Add(const OdometryReading& reading);

  // Takes a reading in a new odometry frame (the base's integrated pose began again: the
  // plausibility check confirmed the jump, odometry_plausibility.h). The motion from the
  // previous reading to it is unknown: it is extrapolated with the last velocities and
  // extrapolation noise, as with no reading; increments are measured from it on.
  void AddInNewFrame(const OdometryReading& reading);

  // Whether any reading has arrived (since construction or Clear()).
  bool anchored() const { return cursor_.has_value(); }

  // Adds to `motion` the robot's motion from the cursor to utime (one eq.-1 step per increment,
  // as above) and moves the cursor to utime. Returns true when readings cover the interval (at
  // least one increment, or the interpolated part of one), false when the motion was only
  // extrapolated or nothing was added (not anchored).
  bool AddMotionTo(int64_t utime, const OdometryNoiseOptions& noise,
                   const ExtrapolationNoise& extrapolation, RobotMotionAccumulator* motion);

  // Forgets every reading and the cursor (the estimator starts over).
  void Clear();

 private:
  struct Cursor {
    int64_t utime = 0;
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();
    double linear_mps = 0.0;
    double angular_radps = 0.0;
  };

  struct Stored {
    OdometryReading reading;
    bool new_frame = false;  // no increment from the reading before it
  };
  // The motion extrapolated from `from` over tau seconds (at most extrapolation.max_s).
  static void AddExtrapolated(const Cursor& from, double tau_s, const OdometryNoiseOptions& noise,
                              const ExtrapolationNoise& extrapolation,
                              RobotMotionAccumulator* motion, OdometryIncrement* part);
  void Store(const OdometryReading& reading, bool new_frame);

  std::optional<Cursor> cursor_;
  std::deque<Stored> readings_;  // newer than the cursor, oldest first
};

}  // namespace slammtt
