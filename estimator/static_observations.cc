#include "estimator/static_observations.h"

#include <algorithm>

namespace slammtt {

std::vector<StaticObservation> StaticObservations(const std::vector<PointMeasurement>& measurements,
                                                  const Assignment& assignment,
                                                  const SlamState& state) {
  std::vector<StaticObservation> observations;
  const int num_measurements =
      std::min(assignment.num_measurements(), static_cast<int>(measurements.size()));
  for (int i = 0; i < num_measurements; ++i) {
    const int j = assignment.ObjectOf(i);
    if (j < 0 || j >= state.num_objects()) continue;
    const PointMeasurement& m = measurements[static_cast<size_t>(i)];
    const ObjectRecord& record = state.object(j).record;
    if (m.person || !MayBePointLandmark(record.object_class, record.kind)) continue;
    const bool landmark = record.object_class == ObjectClass::kStatic && record.confirmed;
    observations.push_back(StaticObservation{record.id, m.range_bearing, m.covariance, !landmark});
  }
  return observations;
}

}  // namespace slammtt
