#include "tools/eval/log_only_scene.h"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

namespace slammtt {
namespace {

// The anchor of the odometry frame in the map frame at the first POSE the odometry covers.
std::optional<Pose2> OdometryAnchor(const std::vector<TimedPose>& estimate,
                                    const std::vector<TimedPose>& odometry) {
  for (const TimedPose& p : estimate) {
    if (const auto o = InterpolatePose(odometry, p.utime)) return AnchorTransform(p.pose, *o);
  }
  return std::nullopt;
}

void ExtendSpan(int64_t utime, int64_t* first, int64_t* last) {
  *first = std::min(*first, utime);
  *last = std::max(*last, utime);
}

}  // namespace

void FillLogOnlyScene(const EvalInput& input, EvaluationReport* report) {
  LogOnlyScene scene;
  scene.estimate = input.estimate;
  const std::optional<Pose2> anchor = OdometryAnchor(input.estimate, input.odometry);
  scene.odometry_anchored_to_estimate = anchor.has_value();
  scene.has_map = input.final_map.has_value();
  scene.has_tracks = !input.tracks.empty();
  for (const TimedPose& o : input.odometry) {
    scene.odometry.push_back({o.utime, anchor ? Compose(*anchor, o.pose) : o.pose});
  }
  int64_t first = std::numeric_limits<int64_t>::max();
  int64_t last = std::numeric_limits<int64_t>::min();
  for (const auto* poses : {&input.estimate, &input.odometry}) {
    for (const TimedPose& p : *poses) ExtendSpan(p.utime, &first, &last);
  }
  if (input.final_map) {
    ExtendSpan(input.final_map_utime, &first, &last);
    for (const LandmarkSample& l : *input.final_map) {
      AnchoredLandmark a;
      a.id = l.id;
      a.position_m = l.position_m;
      a.covariance = l.covariance;
      a.kind = AnchoredLandmark::Kind::kUnjudged;
      report->landmarks.push_back(a);
    }
  }
  std::map<int64_t, TrackPath> paths;
  for (const TrackScan& scan : input.tracks) {
    ExtendSpan(scan.utime, &first, &last);
    for (const TrackSample& t : scan.tracks) {
      if (!t.confirmed || t.label != ObjectLabel::kMoving) continue;
      TrackPath& path = paths[t.id];
      path.id = t.id;
      path.points.push_back(t.position_m);
    }
  }
  for (auto& [id, path] : paths) report->track_paths.push_back(std::move(path));
  if (first <= last) {
    report->first_utime = first;
    report->last_utime = last;
  }
  report->log_only = std::move(scene);
}

}  // namespace slammtt
