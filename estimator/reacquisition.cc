#include "estimator/reacquisition.h"

#include <algorithm>

#include "common/utime.h"
#include "estimator/range_bearing_model.h"

namespace slammtt {
namespace {

bool Contains(const std::vector<int>& list, int value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

// The lost movers of this scan, not taken over.
std::vector<LostTrack> LostTracks(int64_t utime, const std::vector<int>& taken_over,
                                  const TrackManagementOptions& options, const SlamState& state,
                                  const Assignment& assignment) {
  std::vector<LostTrack> lost;
  for (int j = 0; j < assignment.num_objects(); ++j) {
    const StateObject& object = state.object(j);
    if (!IsLostMover(object, assignment.ObjectFree(j), utime, options) || Contains(taken_over, j)) {
      continue;
    }
    lost.push_back({j, object.record.last_seen_m,
                    SecondsBetween(utime, object.record.last_seen_utime)});
  }
  return lost;
}

// The measurements that start new objects and may carry an identity, with their map points.
std::vector<BirthPoint> BirthPoints(const ScanAssociation& scan,
                                    const std::vector<double>& nearest_nis,
                                    const EstimatorOptions& options,
                                    ObservationPredictions* predicted, const SlamState& state,
                                    const Assignment& assignment) {
  const double dn = options.new_object_gate_dn_chi2;
  // A static landmark that got no measurement this scan and lies within twice the new-object
  // gate of a measurement has most likely produced it, with an error out in the tail
  // (s1-crossing's point features: 0.9 m in range at 18 m, 4.6 sigma): such a measurement is
  // not trusted to carry an identity.
  std::vector<int> unmeasured_landmarks;
  for (int j = 0; j < assignment.num_objects(); ++j) {
    if (assignment.ObjectFree(j) && !state.object(j).has_velocity()) {
      unmeasured_landmarks.push_back(j);
    }
  }
  const std::vector<ObjectPrediction>& now = predicted->At(state);
  std::vector<BirthPoint> births;
  for (int i = 0; i < assignment.num_measurements(); ++i) {
    if (!assignment.MeasurementFree(i) || nearest_nis[static_cast<size_t>(i)] < dn) continue;
    const PointMeasurement& z = scan.measurements[static_cast<size_t>(i)];
    const bool landmark_outlier =
        std::any_of(unmeasured_landmarks.begin(), unmeasured_landmarks.end(), [&](int j) {
          return NormalizedInnovationSquared(z, now[static_cast<size_t>(j)], 2.0 * dn) < 2.0 * dn;
        });
    if (landmark_outlier) continue;
    births.push_back({i, PointFromRangeBearing(state.robot_pose(), z.range_bearing,
                                               options.sensor)});
  }
  return births;
}

}  // namespace

bool IsLostMover(const StateObject& object, bool unmeasured, int64_t utime,
                 const TrackManagementOptions& options) {
  const ObjectRecord& record = object.record;
  return unmeasured && object.has_velocity() && record.confirmed &&
         record.object_class == ObjectClass::kMoving &&
         !ReportedConfirmed(record, true, utime, options);
}

std::vector<Reacquisition> ChooseReacquisitions(const std::vector<LostTrack>& lost,
                                                const std::vector<BirthPoint>& births,
                                                double reacquire_speed_mps) {
  struct Pair {
    double ratio;  // distance over reach: how much of the reachable disc the pair uses
    Reacquisition pair;
  };
  std::vector<Pair> pairs;
  if (reacquire_speed_mps <= 0.0) return {};
  for (const BirthPoint& b : births) {
    for (const LostTrack& t : lost) {
      const double reach = reacquire_speed_mps * t.unseen_s;
      const double distance = (b.point_m - t.last_seen_m).norm();
      if (reach > 0.0 && distance <= reach) {
        pairs.push_back({distance / reach, {b.measurement, t.object}});
      }
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.ratio < b.ratio; });
  std::vector<Reacquisition> chosen;
  std::vector<int> used_measurements;
  std::vector<int> used_objects;
  for (const Pair& p : pairs) {
    if (std::find(used_measurements.begin(), used_measurements.end(), p.pair.measurement) !=
            used_measurements.end() ||
        std::find(used_objects.begin(), used_objects.end(), p.pair.object) !=
            used_objects.end()) {
      continue;
    }
    used_measurements.push_back(p.pair.measurement);
    used_objects.push_back(p.pair.object);
    chosen.push_back(p.pair);
  }
  return chosen;
}

std::vector<int64_t> TagPossibleContinuations(const ScanAssociation& scan,
                                              const std::vector<double>& nearest_nis,
                                              const std::vector<int>& taken_over,
                                              const EstimatorOptions& options,
                                              ObservationPredictions* predicted,
                                              const SlamState& state,
                                              const Assignment& assignment) {
  std::vector<int64_t> continues_id(scan.measurements.size(), 0);
  const bool static_world = options.mode == AssociationMode::kStaticNearestNeighbour;
  if (static_world || !(options.tracks.reacquire_speed_mps > 0.0)) return continues_id;
  const std::vector<LostTrack> lost =
      LostTracks(scan.utime, taken_over, options.tracks, state, assignment);
  if (lost.empty()) return continues_id;
  const std::vector<BirthPoint> births =
      BirthPoints(scan, nearest_nis, options, predicted, state, assignment);
  for (const Reacquisition& r :
       ChooseReacquisitions(lost, births, options.tracks.reacquire_speed_mps)) {
    continues_id[static_cast<size_t>(r.measurement)] = state.object(r.object).record.id;
  }
  return continues_id;
}

std::vector<int> TakeOverLostIdentities(int64_t utime, const EstimatorOptions& options,
                                        const Assignment& assignment, SlamState* state,
                                        StepCounts* counts) {
  std::vector<int> taken_over;
  for (int k = 0; k < assignment.num_objects(); ++k) {
    ObjectRecord& candidate = state->object(k).record;
    // (Not "still tentative": with confirm_hits <= 2 its own second hit has just confirmed it.)
    if (candidate.continues_id == 0 || assignment.ObjectFree(k) || candidate.hits < 2) continue;
    const int64_t lost_id = candidate.continues_id;
    candidate.continues_id = 0;
    for (int j = 0; j < assignment.num_objects(); ++j) {
      const StateObject& lost = state->object(j);
      if (lost.record.id != lost_id) continue;
      if (IsLostMover(lost, assignment.ObjectFree(j), utime, options.tracks) &&
          !Contains(taken_over, j)) {
        candidate.id = lost.record.id;
        candidate.first_seen_utime = lost.record.first_seen_utime;
        candidate.hits += lost.record.hits;
        candidate.confirmed = true;
        candidate.object_class = ObjectClass::kMoving;
        state->RemoveAnchor(k);  // a MOVING object keeps no stationary hypothesis
        taken_over.push_back(j);
        ++counts->reacquired;
      }
      break;
    }
  }
  return taken_over;
}

}  // namespace slammtt
