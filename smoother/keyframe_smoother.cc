#include "smoother/keyframe_smoother.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/angle.h"
#include "common/checked_options.h"
#include "common/utime.h"
#include "geometry/pose2.h"

namespace slammtt {
namespace {

using R = OptionRange;

// a * b with its covariance: J_a C_a J_a^T + J_b C_b J_b^T (a and b independent).
void ComposeWithCovariance(const Eigen::Vector3d& a, const Eigen::Matrix3d& a_covariance,
                           const Eigen::Vector3d& b, const Eigen::Matrix3d& b_covariance,
                           Eigen::Vector3d* composed, Eigen::Matrix3d* covariance) {
  const double c = std::cos(a(2));
  const double s = std::sin(a(2));
  Eigen::Matrix3d jacobian_a = Eigen::Matrix3d::Identity();
  jacobian_a(0, 2) = -s * b(0) - c * b(1);
  jacobian_a(1, 2) = c * b(0) - s * b(1);
  Eigen::Matrix3d jacobian_b = Eigen::Matrix3d::Identity();
  jacobian_b.topLeftCorner<2, 2>() << c, -s, s, c;
  *composed = ComposePoses(a, b);
  const Eigen::Matrix3d sum = jacobian_a * a_covariance * jacobian_a.transpose() +
                              jacobian_b * b_covariance * jacobian_b.transpose();
  *covariance = 0.5 * (sum + sum.transpose());
}

Eigen::Matrix3d PoseFloor(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d(sigma_m * sigma_m, sigma_m * sigma_m, sigma_rad * sigma_rad)
      .asDiagonal();
}

// Why an observation cannot be a factor (a range that is not positive, a number that is not
// finite, a covariance that is not positive definite), or nullopt.
std::optional<std::string> ObservationProblem(const StaticObservation& o) {
  const std::string what = "landmark " + std::to_string(o.landmark_id) + ": ";
  if (!o.range_bearing.allFinite() || !(o.range_bearing(0) > 0.0)) {
    return what + "range " + std::to_string(o.range_bearing(0)) + " m, bearing " +
           std::to_string(o.range_bearing(1)) + " rad: not a measurement";
  }
  const Eigen::LLT<Eigen::Matrix2d> llt(o.covariance);
  if (!o.covariance.allFinite() || llt.info() != Eigen::Success ||
      !(o.covariance - o.covariance.transpose()).isZero(1e-12 * o.covariance.norm())) {
    return what + "measurement covariance is not symmetric positive definite";
  }
  return std::nullopt;
}

}  // namespace

void VisitKeyframeSmootherOptions(OptionVisitor* v, KeyframeSmootherOptions* o) {
  v->Double("keyframe_distance_m", &o->keyframe_distance_m, R::AtLeast(0),
            "a keyframe when the robot moved this far since the last one (0: not this rule)");
  v->Double("keyframe_rotation_rad", &o->keyframe_rotation_rad, R::Between(0, 180),
            "... or turned this much (0: not this rule)", OptionUnit::kDegrees);
  v->Double("keyframe_interval_s", &o->keyframe_interval_s, R::AtLeast(0),
            "... or this much time passed (all three 0: every scan is a keyframe)");
  v->Int("optimize_every_keyframes", &o->optimize_every_keyframes, R::Between(0, 1e9),
         "a batch Levenberg-Marquardt solve every this many keyframes (0: never)");
  v->Double("odometry_min_sigma_m", &o->odometry_min_sigma_m, R::Above(0),
            "added in quadrature to each scan's odometry increment, x and y");
  v->Double("odometry_min_sigma_rad", &o->odometry_min_sigma_rad, R::Above(0),
            "the same for its heading", OptionUnit::kDegrees);
  v->Double("odometry_variance_scale_forward", &o->odometry_variance_scale_forward, R::Above(0),
            "factor on the variance of each scan's odometry increment along the heading");
  v->Double("odometry_variance_scale_sideways", &o->odometry_variance_scale_sideways,
            R::Above(0), "... sideways");
  v->Double("odometry_variance_scale_heading", &o->odometry_variance_scale_heading, R::Above(0),
            "... in heading");
  v->Double("prior_min_sigma_m", &o->prior_min_sigma_m, R::Above(0),
            "added in quadrature to the filter's first pose covariance, x and y");
  v->Double("prior_min_sigma_rad", &o->prior_min_sigma_rad, R::Above(0),
            "the same for its heading", OptionUnit::kDegrees);
  v->Bool("covariances", &o->covariances,
          "publish the marginal covariances of the pose and the landmarks");
  v->Int("max_held_observations", &o->max_held_observations, R::Between(0, 1e9),
         "tentative observations held per object until it is a static landmark");
  v->Bool("between_keyframe_observations", &o->between_keyframe_observations,
          "the observations of scans between keyframes: factors on the last keyframe through "
          "the motion since it (false: left out)");
  v->Double("between_keyframe_variance_scale", &o->between_keyframe_variance_scale,
            R::AtLeast(0),
            "factor on the motion's covariance added to those observations' covariance");
  v->Int("map_every_keyframes", &o->map_every_keyframes, R::Between(1, 1e9),
         "SMOOTHED_MAP at every this many keyframes (its covariances cost the most)");
  v->BeginGroup("solver");
  VisitSmootherOptions(v, &o->solver);
  v->EndGroup();
}

std::string CheckKeyframeSmootherOptions(const KeyframeSmootherOptions& options) {
  KeyframeSmootherOptions o = options;
  OptionRangeCheck check;
  VisitKeyframeSmootherOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  // The solver's own rules beyond its ranges (max_lambda >= initial_lambda).
  const std::string solver_problem = CheckSmootherOptions(o.solver);
  return solver_problem.empty() ? "" : "solver: " + solver_problem;
}

KeyframeSmoother::KeyframeSmoother(const KeyframeSmootherOptions& options)
    : options_(CheckedOptions(options, &CheckKeyframeSmootherOptions, "smoother options")) {}

SmoothedScan KeyframeSmoother::AddScan(const SmootherScanInput& scan) {
  SmoothedScan out;
  out.utime = scan.utime;
  if (last_utime_ && scan.utime <= *last_utime_ && scan.continues) {
    ++counters_.scans_out_of_order;
    return out;
  }
  last_utime_ = scan.utime;
  ++counters_.scans;
  out.processed = true;
  if (!scan.continues || !smoother_) {
    StartProblem(scan);
    out.keyframe = true;
    Solve(&out);
    FillPose(&out);
    return out;
  }
  RemoveLandmarks(scan.removed_landmark_ids);
  AccumulateMotion(scan);
  if (IsKeyframe(scan.utime)) {
    AddKeyframe(scan, &out);
    Solve(&out);
  } else {
    counters_.observations_between_keyframes += static_cast<int64_t>(scan.observations.size());
    if (options_.between_keyframe_observations) {
      // The scan's sightings are the larger part of what the scans say (7 of 8 with a keyframe
      // every metre at 1 m/s and 8 Hz); without them the map's rotation about the first pose
      // rests on a few keyframes' bearings (docs/smoother.md, "Large loop").
      const SensorMount mount = MountSinceKeyframe(scan.mount);
      FuseObservations(scan, mount, MotionCovarianceOfObservations(scan, mount));
    }
  }
  FillPose(&out);
  return out;
}

void KeyframeSmoother::StartProblem(const SmootherScanInput& scan) {
  if (smoother_) ++counters_.restarts;
  smoother_ = std::make_unique<Smoother>(options_.solver);
  keyframe_utimes_.clear();
  held_.clear();
  fused_.clear();
  keyframes_since_batch_ = 0;
  motion_.setZero();
  motion_covariance_.setZero();
  keyframe_utimes_.push_back(scan.utime);
  ++counters_.keyframes;
  Eigen::Vector3d pose = scan.pose;
  if (!pose.allFinite()) {
    Refused("first pose is not finite: the map frame's origin taken instead");
    pose.setZero();
  }
  Refused(smoother_->AddPose(0, pose));
  const Eigen::Matrix3d covariance =
      scan.pose_covariance + PoseFloor(options_.prior_min_sigma_m, options_.prior_min_sigma_rad);
  std::optional<std::string> error = smoother_->AddPosePrior(0, pose, covariance.inverse());
  if (error) {
    // A covariance that is not usable: the floor alone anchors the map frame.
    Refused(error);
    Refused(smoother_->AddPosePrior(
        0, pose,
        PoseFloor(options_.prior_min_sigma_m, options_.prior_min_sigma_rad).inverse()));
  }
  AddObservations(scan);
}

void KeyframeSmoother::AccumulateMotion(const SmootherScanInput& scan) {
  // D C D with D = diag(sqrt(scales)): the variances scaled, the correlations kept.
  const Eigen::Vector3d root = Eigen::Vector3d(options_.odometry_variance_scale_forward,
                                               options_.odometry_variance_scale_sideways,
                                               options_.odometry_variance_scale_heading)
                                   .cwiseSqrt();
  const Eigen::Matrix3d increment_covariance =
      root.asDiagonal() * scan.increment_covariance * root.asDiagonal() +
      PoseFloor(options_.odometry_min_sigma_m, options_.odometry_min_sigma_rad);
  if (!scan.increment.allFinite() || !increment_covariance.allFinite()) {
    Refused(std::string("odometry increment is not finite: taken as standing still"));
    ComposeWithCovariance(motion_, motion_covariance_, Eigen::Vector3d::Zero(),
                          PoseFloor(options_.odometry_min_sigma_m, options_.odometry_min_sigma_rad),
                          &motion_, &motion_covariance_);
    return;
  }
  ComposeWithCovariance(motion_, motion_covariance_, scan.increment, increment_covariance,
                        &motion_, &motion_covariance_);
}

bool KeyframeSmoother::IsKeyframe(int64_t utime) const {
  const KeyframeSmootherOptions& o = options_;
  if (o.keyframe_distance_m == 0.0 && o.keyframe_rotation_rad == 0.0 &&
      o.keyframe_interval_s == 0.0) {
    return true;
  }
  if (o.keyframe_distance_m > 0.0 && motion_.head<2>().norm() >= o.keyframe_distance_m) {
    return true;
  }
  if (o.keyframe_rotation_rad > 0.0 && std::abs(motion_(2)) >= o.keyframe_rotation_rad) {
    return true;
  }
  return o.keyframe_interval_s > 0.0 &&
         SecondsBetween(utime, LastKeyframeUtime()) >= o.keyframe_interval_s;
}

void KeyframeSmoother::AddKeyframe(const SmootherScanInput& scan, SmoothedScan* out) {
  FlushFused();
  const PoseId id = LastKeyframe() + 1;
  const Eigen::LLT<Eigen::Matrix3d> llt(motion_covariance_);
  if (llt.info() != Eigen::Success || !motion_covariance_.allFinite()) {
    // Cannot happen with the floor added to every increment; kept so that a keyframe never
    // floats free of its odometry.
    Refused("odometry covariance since keyframe " + std::to_string(LastKeyframe()) +
            " is not positive definite: the floor taken instead");
    motion_covariance_ = PoseFloor(options_.odometry_min_sigma_m, options_.odometry_min_sigma_rad);
  }
  const Eigen::Vector3d start = ComposePoses(*smoother_->PoseEstimate(LastKeyframe()), motion_);
  std::optional<std::string> error = smoother_->AddPose(id, start);
  if (error) {
    Refused(error);
    return;
  }
  error = smoother_->AddOdometry(LastKeyframe(), id, motion_, motion_covariance_.inverse());
  if (error) {
    // Without its odometry the keyframe would float free: it leaves the problem unused.
    Refused(error);
    return;
  }
  keyframe_utimes_.push_back(scan.utime);
  motion_.setZero();
  motion_covariance_.setZero();
  ++counters_.keyframes;
  out->keyframe = true;
  AddObservations(scan);
}

SensorMount KeyframeSmoother::MountSinceKeyframe(const SensorMount& mount) const {
  const Eigen::Vector3d laser =
      ComposePoses(motion_, Eigen::Vector3d(mount.forward_m, mount.left_m, mount.yaw_rad));
  SensorMount since;
  since.forward_m = laser(0);
  since.left_m = laser(1);
  since.yaw_rad = WrapAngle(laser(2));
  return since;
}

std::vector<Eigen::Matrix2d> KeyframeSmoother::MotionCovarianceOfObservations(
    const SmootherScanInput& scan, const SensorMount& mount) const {
  // The landmark fixed in the keyframe's frame, (range, bearing) as a function of the motion
  // m = (x, y, theta) since the keyframe: the laser at t = (x, y) + R(theta) (a, b), heading
  // theta + yaw; dr = -u . dt, dbearing = (n . dt) / r... with u the ray's direction, n its
  // left normal: dbearing = -(n . dt) / r - dtheta (paper eq. 10 differentiated).
  const Eigen::Vector2d lever(-std::sin(motion_(2)) * scan.mount.forward_m -
                                  std::cos(motion_(2)) * scan.mount.left_m,
                              std::cos(motion_(2)) * scan.mount.forward_m -
                                  std::sin(motion_(2)) * scan.mount.left_m);
  std::vector<Eigen::Matrix2d> added;
  added.reserve(scan.observations.size());
  for (const StaticObservation& o : scan.observations) {
    const double range = std::max(o.range_bearing(0), 1e-3);
    const double angle = mount.yaw_rad + o.range_bearing(1);
    const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d n(-u(1), u(0));
    Eigen::Matrix<double, 2, 3> jacobian;
    jacobian << -u(0), -u(1), -u.dot(lever), -n(0) / range, -n(1) / range,
        -n.dot(lever) / range - 1.0;
    const Eigen::Matrix2d c = jacobian * motion_covariance_ * jacobian.transpose();
    added.push_back(options_.between_keyframe_variance_scale * 0.5 * (c + c.transpose()));
  }
  return added;
}

void KeyframeSmoother::AddObservations(const SmootherScanInput& scan, const SensorMount& mount) {
  for (const StaticObservation& o : scan.observations) {
    // Checked before a new landmark is added: a landmark without its factor would leave the
    // problem unconstrained.
    const std::optional<std::string> problem = ObservationProblem(o);
    if (problem) {
      Refused(problem);
      continue;
    }
    if (!smoother_->LandmarkEstimate(o.landmark_id)) {
      if (o.tentative) {
        Hold(o, mount);
        continue;
      }
      if (!AddLandmarkWithHeld(o, mount)) continue;
    }
    AddRangeBearing(LastKeyframe(), o, mount);
  }
}

void KeyframeSmoother::FuseObservations(const SmootherScanInput& scan, const SensorMount& mount,
                                        const std::vector<Eigen::Matrix2d>& extra_covariance) {
  SmootherScanInput rest = scan;
  rest.observations.clear();
  for (size_t k = 0; k < scan.observations.size(); ++k) {
    StaticObservation o = scan.observations[k];
    if (k < extra_covariance.size() && extra_covariance[k].allFinite()) {
      o.covariance += extra_covariance[k];
    }
    if (ObservationProblem(o) || !smoother_->LandmarkEstimate(o.landmark_id)) {
      rest.observations.push_back(o);  // refused, held or a new landmark: one by one
      continue;
    }
    // The point in the keyframe's frame and its covariance J C J^T, J = d point / d (range,
    // bearing) = [u, r n] (u the ray's direction, n its left normal).
    const Eigen::Vector2d point =
        PointFromRangeBearing(Eigen::Vector3d::Zero(), o.range_bearing, mount);
    const double angle = mount.yaw_rad + o.range_bearing(1);
    Eigen::Matrix2d jacobian;
    jacobian << std::cos(angle), -o.range_bearing(0) * std::sin(angle), std::sin(angle),
        o.range_bearing(0) * std::cos(angle);
    const Eigen::Matrix2d covariance = jacobian * o.covariance * jacobian.transpose();
    const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (covariance + covariance.transpose()));
    if (llt.info() != Eigen::Success) {
      Refused("landmark " + std::to_string(o.landmark_id) +
              ": observation's position covariance is not positive definite");
      continue;
    }
    const Eigen::Matrix2d information = llt.solve(Eigen::Matrix2d::Identity());
    Fused& fused = fused_[o.landmark_id];
    fused.information += information;
    fused.information_vector += information * point;
    ++counters_.observations_used;
  }
  AddObservations(rest, mount);
}

void KeyframeSmoother::FlushFused() {
  for (const auto& [id, fused] : fused_) {
    if (!smoother_->LandmarkEstimate(id)) continue;  // removed meanwhile
    const Eigen::Matrix2d information = 0.5 * (fused.information + fused.information.transpose());
    const Eigen::Vector2d position = information.ldlt().solve(fused.information_vector);
    Refused(smoother_->AddRelativePosition(LastKeyframe(), id, position, information));
  }
  fused_.clear();
}

void KeyframeSmoother::Hold(const StaticObservation& observation, const SensorMount& mount) {
  std::deque<Held>& held = held_[observation.landmark_id];
  held.push_back(Held{LastKeyframe(), observation, mount});
  ++counters_.observations_held;
  if (static_cast<int>(held.size()) > options_.max_held_observations) {
    held.pop_front();
    ++counters_.held_observations_dropped;
  }
}

bool KeyframeSmoother::AddLandmarkWithHeld(const StaticObservation& observation,
                                           const SensorMount& mount) {
  const auto held = held_.find(observation.landmark_id);
  const bool has_held = held != held_.end() && !held->second.empty();
  const PoseId first_pose = has_held ? held->second.front().keyframe : LastKeyframe();
  const Eigen::Vector2d first_range_bearing =
      has_held ? held->second.front().observation.range_bearing : observation.range_bearing;
  const SensorMount first_mount = has_held ? held->second.front().mount : mount;
  const std::optional<std::string> error = smoother_->AddLandmark(
      observation.landmark_id, PointFromRangeBearing(*smoother_->PoseEstimate(first_pose),
                                                     first_range_bearing, first_mount));
  if (error) {
    Refused(error);
    return false;
  }
  if (has_held) {
    for (const Held& h : held->second) AddRangeBearing(h.keyframe, h.observation, h.mount);
    held_.erase(held);
  }
  return true;
}

void KeyframeSmoother::AddRangeBearing(PoseId pose, const StaticObservation& o,
                                       const SensorMount& mount) {
  const std::optional<std::string> error = smoother_->AddRangeBearing(
      pose, o.landmark_id, o.range_bearing, o.covariance.inverse(), mount);
  if (error) {
    Refused(error);
  } else {
    ++counters_.observations_used;
  }
}

void KeyframeSmoother::RemoveLandmarks(const std::vector<int64_t>& ids) {
  for (const int64_t id : ids) {
    fused_.erase(id);
    const auto held = held_.find(id);
    if (held != held_.end()) {
      counters_.held_observations_dropped += static_cast<int64_t>(held->second.size());
      held_.erase(held);
    }
    // A landmark the smoother never got (its observations fell between keyframes) is no error.
    if (!smoother_->LandmarkEstimate(id)) continue;
    Refused(smoother_->RemoveLandmark(id));
    ++counters_.landmarks_removed;
  }
}

void KeyframeSmoother::Refused(const std::optional<std::string>& error) {
  if (!error) return;
  ++counters_.inputs_refused;
  last_error_ = *error;
}

void KeyframeSmoother::Solve(SmoothedScan* out) {
  out->update = smoother_->Update();
  if (!out->update.ok) {
    ++counters_.solves_failed;
    last_error_ = "update: " + out->update.error;
  }
  last_keyframe_covariance_.reset();
  if (options_.optimize_every_keyframes > 0 &&
      ++keyframes_since_batch_ >= options_.optimize_every_keyframes) {
    keyframes_since_batch_ = 0;
    out->batch = smoother_->Optimize();
    ++counters_.batch_optimizations;
    if (!out->batch->ok) {
      ++counters_.solves_failed;
      last_error_ = "optimize: " + out->batch->error;
    }
  }
}

void KeyframeSmoother::FillPose(SmoothedScan* out) {
  const Eigen::Vector3d keyframe = *smoother_->PoseEstimate(LastKeyframe());
  out->pose = ComposePoses(keyframe, motion_);
  out->pose(2) = WrapAngle(out->pose(2));
  if (!options_.covariances) return;
  if (!last_keyframe_covariance_) {
    const std::optional<Eigen::Matrix3d> covariance = smoother_->PoseCovariance(LastKeyframe());
    last_keyframe_covariance_ = covariance ? *covariance : Eigen::Matrix3d::Zero();
  }
  Eigen::Vector3d composed;
  ComposeWithCovariance(keyframe, *last_keyframe_covariance_, motion_, motion_covariance_,
                        &composed, &out->pose_covariance);
}

std::vector<SmoothedLandmark> KeyframeSmoother::Landmarks() {
  std::vector<SmoothedLandmark> landmarks;
  if (!smoother_) return landmarks;
  const std::vector<LandmarkId> ids = smoother_->LandmarkIds();
  std::vector<std::optional<Eigen::Matrix2d>> covariances;
  if (options_.covariances) covariances = smoother_->LandmarkCovariances(ids);
  for (size_t k = 0; k < ids.size(); ++k) {
    SmoothedLandmark landmark;
    landmark.id = ids[k];
    landmark.position = *smoother_->LandmarkEstimate(ids[k]);
    if (k < covariances.size() && covariances[k]) landmark.covariance = *covariances[k];
    landmarks.push_back(landmark);
  }
  return landmarks;
}

std::vector<std::pair<int64_t, Eigen::Vector3d>> KeyframeSmoother::Keyframes() const {
  std::vector<std::pair<int64_t, Eigen::Vector3d>> keyframes;
  if (!smoother_) return keyframes;
  const std::vector<PoseId> ids = smoother_->PoseIds();
  for (const PoseId id : ids) {
    if (id < 0 || static_cast<size_t>(id) >= keyframe_utimes_.size()) continue;
    keyframes.emplace_back(keyframe_utimes_[static_cast<size_t>(id)], *smoother_->PoseEstimate(id));
  }
  return keyframes;
}

}  // namespace slammtt
