#include "estimator/landmark_window.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace slammtt {

void VisitLandmarkWindowOptions(OptionVisitor* v, LandmarkWindowOptions* o) {
  using R = OptionRange;
  v->Double("radius_m", &o->radius_m, R::AtLeast(0),
            "static landmarks farther from the robot leave the state for the archive (0: off)");
  v->Double("reenter_radius_m", &o->reenter_radius_m, R::AtLeast(0),
            "archived landmarks nearer re-enter the state (in [max_range_m, radius_m])");
  v->Int("max_landmarks", &o->max_landmarks, R::Between(0, 100000),
         "confirmed static landmarks in the state at most, the farthest leave (0: no limit)");
}

std::string CheckLandmarkWindowOptions(const LandmarkWindowOptions& o, double max_range_m) {
  if (o.radius_m == 0.0) {
    if (o.max_landmarks != 0) return "window_max_landmarks needs window_radius_m > 0";
    return "";
  }
  if (!(o.reenter_radius_m <= o.radius_m)) {
    return "window_reenter_radius_m must be <= window_radius_m";
  }
  if (!(o.reenter_radius_m >= max_range_m)) {
    return "window_reenter_radius_m must be >= max_range_m (a landmark the laser can see must "
           "be in the state)";
  }
  return "";
}

bool MayLeaveTheState(const SlamState& state, int k) {
  const StateObject& o = state.object(k);
  return !o.has_velocity() && o.record.confirmed &&
         o.record.object_class == ObjectClass::kStatic && o.record.kind == ObjectKind::kOther;
}

namespace {

double DistanceFromRobot(const SlamState& state, const Eigen::Vector2d& point) {
  return (point - state.robot_pose().head<2>()).norm();
}

int NumLandmarksThatMayLeave(const SlamState& state) {
  int n = 0;
  for (int k = 0; k < state.num_objects(); ++k) n += MayLeaveTheState(state, k) ? 1 : 0;
  return n;
}

}  // namespace

int LandmarkArchive::Restore(const LandmarkWindowOptions& options, SlamState* state) {
  if (options.radius_m <= 0.0 || landmarks_.empty()) return 0;
  std::vector<std::pair<double, int64_t>> near;  // (distance, id): nearest first, then lower id
  for (const auto& [id, landmark] : landmarks_) {
    const double distance = DistanceFromRobot(*state, landmark.position_m);
    if (distance <= options.reenter_radius_m) near.emplace_back(distance, id);
  }
  if (near.empty()) return 0;
  std::sort(near.begin(), near.end());
  int room = static_cast<int>(near.size());
  if (options.max_landmarks > 0) {
    room = std::min(room, std::max(0, options.max_landmarks - NumLandmarksThatMayLeave(*state)));
  }
  const Eigen::Matrix<double, 2, 3> uncorrelated = Eigen::Matrix<double, 2, 3>::Zero();
  for (int i = 0; i < room; ++i) {
    const auto it = landmarks_.find(near[static_cast<size_t>(i)].second);
    ObjectRecord record = it->second.record;
    // What described the scans before it left says nothing about the scans to come.
    record.unseen_in_view_s = 0.0;
    record.unseen_observable_s = 0.0;
    record.num_offsets = 0;
    record.next_offset = 0;
    record.reentered_unseen = true;
    state->AddObject(it->second.position_m, uncorrelated, it->second.covariance_m2, record);
    landmarks_.erase(it);
  }
  return room;
}

int LandmarkArchive::Archive(const LandmarkWindowOptions& options, SlamState* state) {
  if (options.radius_m <= 0.0) return 0;
  std::vector<std::pair<double, int>> candidates;  // (distance, index): farthest last
  for (int k = 0; k < state->num_objects(); ++k) {
    if (!MayLeaveTheState(*state, k)) continue;
    candidates.emplace_back(DistanceFromRobot(*state, state->position(k)), k);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> leaving;
  const size_t kept_at_most =
      options.max_landmarks > 0 ? static_cast<size_t>(options.max_landmarks) : candidates.size();
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].first > options.radius_m || i >= kept_at_most) {
      leaving.push_back(candidates[i].second);
    }
  }
  Store(*state, leaving);
  state->RemoveObjects(leaving);
  return static_cast<int>(leaving.size());
}

bool LandmarkArchive::MoveLandmark(int64_t id, const Eigen::Vector2d& position_m) {
  const auto it = landmarks_.find(id);
  if (it == landmarks_.end()) return false;
  it->second.position_m = position_m;
  return true;
}

int LandmarkArchive::Store(const SlamState& state, const std::vector<int>& indices) {
  int stored = 0;
  for (const int k : indices) {
    if (k < 0 || k >= state.num_objects() || !MayLeaveTheState(state, k)) continue;
    ArchivedLandmark landmark;
    landmark.position_m = state.position(k);
    landmark.covariance_m2 = state.ObjectCovariance(k).topLeftCorner<2, 2>();
    landmark.record = state.object(k).record;
    landmarks_[landmark.record.id] = landmark;
    ++stored;
  }
  return stored;
}

}  // namespace slammtt
