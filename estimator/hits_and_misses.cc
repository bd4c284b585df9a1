#include "estimator/hits_and_misses.h"

#include <algorithm>
#include <cmath>

#include "estimator/people.h"
#include "estimator/track_management.h"

namespace slammtt {

void RecordHitsAndMisses(const ScanAssociation& scan, const std::vector<double>& widths_m,
                         double gap_s, const EstimatorOptions& options,
                         const std::vector<ObjectPrediction>& after_updates,
                         const Assignment& assignment, SlamState* state) {
  const bool static_world = options.mode == AssociationMode::kStaticNearestNeighbour;
  // What the scan saw, for the shadows: (range, bearing, width) of every measurement.
  std::vector<Eigen::Vector3d> seen;
  seen.reserve(scan.measurements.size());
  for (size_t i = 0; i < scan.measurements.size(); ++i) {
    seen.emplace_back(scan.measurements[i].range_bearing(0), scan.measurements[i].range_bearing(1),
                      widths_m[i]);
  }
  const double detection_range =
      options.detection_range_m > 0.0 ? options.detection_range_m : options.max_range_m;
  const SlamState& now = *state;
  const FieldOfView view = FieldOfViewOf(options);
  for (int j = 0; j < assignment.num_objects(); ++j) {
    ObjectRecord& record = state->object(j).record;
    if (!assignment.ObjectFree(j)) {
      RecordHit(scan.utime, options.tracks, &record);
      const int i = assignment.MeasurementOf(j);
      const PointMeasurement& z = scan.measurements[static_cast<size_t>(i)];
      RecordMeasurementKind(z.person, &record);
      if (z.person && z.pair_confidence > 0.0) ++record.pair_hits;
      record.last_seen_m = now.position(j);
      continue;
    }
    if (static_world) continue;
    const ObjectPrediction& p = after_updates[static_cast<size_t>(j)];
    const int position_index = now.object(j).position_index;
    const Eigen::Matrix2d position_cov =
        now.covariance().block<2, 2>(position_index, position_index);
    const double sigma = std::sqrt(std::max(position_cov(0, 0), position_cov(1, 1)));
    const bool in_geometry = p.valid && SurelyInGeometry(p.range_bearing, sigma,
                                                         options.max_range_m, view);
    RecordMiss(gap_s, in_geometry,
               in_geometry && ExpectedVisible(p.range_bearing, sigma, seen, detection_range,
                                              view, options.tracks.shadow_radius_m),
               &record);
  }
}

}  // namespace slammtt
