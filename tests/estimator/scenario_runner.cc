#include "tests/estimator/scenario_runner.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace slammtt::testing {

RunSummary RunScenario(PointWorld* world, Estimator* estimator, int scans, uint64_t seed,
                       double match_m) {
  RunSummary summary;
  std::mt19937_64 rng(seed);
  double ate_sum = 0.0;
  double odometry_sum = 0.0;
  for (int k = 0; k < scans; ++k) {
    const WorldFrame frame = world->Next();
    for (const OdometryReading& reading : frame.odometry) estimator->AddOdometry(reading);
    const ScanResult result = estimator->ProcessScan(frame.scan, &rng);
    const double t = 1e-6 * static_cast<double>(frame.utime);
    const double error = (result.pose.head<2>() - frame.true_pose.head<2>()).norm();
    ate_sum += error * error;
    summary.max_position_error_m = std::max(summary.max_position_error_m, error);
    const double odometry_error = (frame.odometry_pose.head<2>() - frame.true_pose.head<2>()).norm();
    odometry_sum += odometry_error * odometry_error;
    for (int64_t id : frame.feature_truth_ids) {
      ObjectHistory& h = summary.objects[id];
      if (h.first_seen_s < 0.0) h.first_seen_s = t;
      ++h.scans_visible;
    }
    // CLEAR-MOT matching (Bernardin and Stiefelhagen 2008): a correspondence of the previous
    // scan that is still within match_m is kept; the others go to the nearest free estimate.
    std::map<int64_t, const ObjectEstimate*> match_of;
    std::map<int64_t, int64_t> claimed;  // estimate id -> truth id
    for (const TruthObject& truth : frame.objects) {
      const ObjectHistory& h = summary.objects[truth.id];
      if (h.last_matched_id == 0) continue;
      for (const ObjectEstimate& e : result.objects) {
        if (e.id == h.last_matched_id && (e.position - truth.position_m).norm() < match_m) {
          match_of[truth.id] = &e;
          claimed[e.id] = truth.id;
        }
      }
    }
    for (const TruthObject& truth : frame.objects) {
      ObjectHistory& h = summary.objects[truth.id];
      h.mover = truth.mover;
      if (h.first_seen_s < 0.0) continue;
      const ObjectEstimate* match = match_of.count(truth.id) ? match_of[truth.id] : nullptr;
      if (match == nullptr) {
        double best = match_m;
        for (const ObjectEstimate& e : result.objects) {
          const double d = (e.position - truth.position_m).norm();
          if (d < best && claimed.count(e.id) == 0) {
            best = d;
            match = &e;
          }
        }
        if (match != nullptr) claimed[match->id] = truth.id;
      }
      if (match == nullptr) continue;
      ++h.scans_matched;
      if (h.last_matched_id != 0 && h.last_matched_id != match->id) ++h.id_switches;
      h.last_matched_id = match->id;
      if (match->object_class == ObjectClass::kMoving && match->confirmed) {
        if (h.first_moving_s < 0.0) h.first_moving_s = t;
        h.last_moving_s = t;
      }
      if (match->object_class == ObjectClass::kStatic) {
        if (h.first_static_s < 0.0) h.first_static_s = t;
        h.last_static_s = t;
      }
    }
    if (k == scans - 1) {
      // A final STATIC estimate is "a mover in the map" when its nearest truth object is a
      // mover within match_m.
      for (const ObjectEstimate& e : result.objects) {
        if (e.object_class != ObjectClass::kStatic) continue;
        const TruthObject* nearest = nullptr;
        double best = match_m;
        for (const TruthObject& truth : frame.objects) {
          const double d = (e.position - truth.position_m).norm();
          if (d < best) {
            best = d;
            nearest = &truth;
          }
        }
        if (nearest != nullptr && nearest->mover) ++summary.movers_in_final_map;
      }
      for (const TruthObject& truth : frame.objects) {
        if (truth.mover || summary.objects[truth.id].first_seen_s < 0.0) continue;
        ++summary.static_total;
        for (const ObjectEstimate& e : result.objects) {
          if (e.object_class == ObjectClass::kStatic &&
              (e.position - truth.position_m).norm() < match_m) {
            ++summary.static_labelled_static;
            break;
          }
        }
      }
      summary.last = result;
    }
  }
  summary.ate_rmse_m = std::sqrt(ate_sum / scans);
  summary.odometry_rmse_m = std::sqrt(odometry_sum / scans);
  summary.counters = estimator->counters();
  summary.hypotheses = summary.counters.hypotheses_generated;
  return summary;
}

std::string Describe(const RunSummary& s) {
  std::ostringstream out;
  out << "ate_rmse " << s.ate_rmse_m << " m, odometry_rmse " << s.odometry_rmse_m
      << " m, max error " << s.max_position_error_m << " m, hypotheses " << s.hypotheses
      << ", movers in final map " << s.movers_in_final_map << ", static labelled "
      << s.static_labelled_static << "/" << s.static_total << "\n";
  for (const auto& [id, h] : s.objects) {
    out << "  object " << id << (h.mover ? " mover" : " static") << ": seen " << h.first_seen_s
        << " s, moving " << h.first_moving_s << ".." << h.last_moving_s << " s, static "
        << h.first_static_s << ".." << h.last_static_s << " s, switches " << h.id_switches
        << ", matched " << h.scans_matched << "/" << h.scans_visible << "\n";
  }
  return out.str();
}

}  // namespace slammtt::testing
