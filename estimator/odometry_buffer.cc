#include "estimator/odometry_buffer.h"

#include <algorithm>

#include "common/angle.h"
#include "common/utime.h"

namespace slammtt {

void OdometryBuffer::Add(const OdometryReading& reading) { Store(reading, false); }

void OdometryBuffer::AddInNewFrame(const OdometryReading& reading) { Store(reading, true); }

void OdometryBuffer::Store(const OdometryReading& reading, bool new_frame) {
  OdometryReading r = reading;
  r.pose(2) = WrapAngle(r.pose(2));
  if (!cursor_) {
    cursor_ = Cursor{r.utime, r.pose, r.linear_mps, r.angular_radps};
    return;
  }
  if (r.utime <= cursor_->utime) {
    // Late reading (older than the last scan): its velocities are the freshest we have. In a
    // new frame, its pose is the frame's anchor.
    cursor_->linear_mps = r.linear_mps;
    cursor_->angular_radps = r.angular_radps;
    if (new_frame) cursor_->pose = r.pose;
    return;
  }
  readings_.push_back(Stored{r, new_frame});
}

void OdometryBuffer::AddExtrapolated(const Cursor& from, double tau_s,
                                     const OdometryNoiseOptions& noise,
                                     const ExtrapolationNoise& extrapolation,
                                     RobotMotionAccumulator* motion, OdometryIncrement* part) {
  const double tau = std::min(tau_s, extrapolation.max_s);
  *part = OdometryIncrement{from.linear_mps * tau, from.angular_radps * tau};
  Eigen::Matrix2d covariance = OdometryIncrementCovariance(*part, tau, noise);
  covariance(0, 0) += extrapolation.speed_var_per_s2 * tau * tau;
  covariance(1, 1) += extrapolation.turn_var_per_s2 * tau * tau;
  motion->Add(*part, covariance);
}

bool OdometryBuffer::AddMotionTo(int64_t utime, const OdometryNoiseOptions& noise,
                                 const ExtrapolationNoise& extrapolation,
                                 RobotMotionAccumulator* motion) {
  if (!cursor_) return false;
  bool covered = false;
  Cursor previous = *cursor_;
  OdometryIncrement part;
  while (!readings_.empty() && readings_.front().reading.utime <= utime) {
    const OdometryReading& r = readings_.front().reading;
    if (readings_.front().new_frame) {
      // Across a jump of the odometry frame: as if there had been no reading.
      AddExtrapolated(previous, SecondsBetween(r.utime, previous.utime), noise, extrapolation,
                      motion, &part);
    } else {
      const OdometryIncrement increment = IncrementBetweenOdometryPoses(previous.pose, r.pose);
      motion->Add(increment, OdometryIncrementCovariance(
                                 increment, SecondsBetween(r.utime, previous.utime), noise));
      covered = true;
    }
    previous = Cursor{r.utime, r.pose, r.linear_mps, r.angular_radps};
    readings_.pop_front();
  }
  if (!readings_.empty() && !readings_.front().new_frame) {
    // The scan falls between two readings: the part of the next increment up to the scan.
    const OdometryReading& next = readings_.front().reading;
    const double fraction = MicrosecondsBetween(utime, previous.utime) /
                            MicrosecondsBetween(next.utime, previous.utime);
    const OdometryIncrement full = IncrementBetweenOdometryPoses(previous.pose, next.pose);
    part = OdometryIncrement{fraction * full.distance_m, fraction * full.rotation_rad};
    motion->Add(part,
                OdometryIncrementCovariance(part, SecondsBetween(utime, previous.utime), noise));
    cursor_ = Cursor{utime, PredictRobotPose(previous.pose, part), next.linear_mps,
                     next.angular_radps};
    return true;
  }
  // No reading at or after the scan yet (or the next one is in a new frame): extrapolate with
  // the last velocities, with noise that grows with the extrapolated time.
  AddExtrapolated(previous, SecondsBetween(utime, previous.utime), noise, extrapolation, motion,
                  &part);
  cursor_ = Cursor{utime, PredictRobotPose(previous.pose, part), previous.linear_mps,
                   previous.angular_radps};
  return covered;
}

void OdometryBuffer::Clear() {
  cursor_.reset();
  readings_.clear();
}

}  // namespace slammtt
