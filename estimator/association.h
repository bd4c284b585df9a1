// What the association levels of Algorithm 2 share (lines 5-9): the assignment of one scan's
// measurements to objects, applying a level's chosen pairs to the state, and the greedy
// one-to-one choice.
//
// Every level (level1.h, ransac_level.h, level3.h; the nearest-neighbour baseline,
// nearest_neighbour.h) chooses pairs between measurements and objects that are both still free,
// then applies them with ApplyPairs: each pair is gated once more at the state as it is then
// (the state earlier pairs of the same scan left), and only the pairs inside the gate are
// assigned. A pair whose object may not update the state this scan (the static-landmark budget,
// update_budget.h) is assigned all the same but does not update.
#pragma once

#include <cstdint>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/gating.h"
#include "estimator/observation_predictions.h"
#include "estimator/point_measurement.h"
#include "estimator/slam_state.h"
#include "estimator/step_counts.h"

namespace slammtt {

// Which object each measurement of the scan got, and the reverse (-1: none).
class Assignment {
 public:
  Assignment(int num_measurements, int num_objects);
  int num_measurements() const { return static_cast<int>(object_of_measurement_.size()); }
  int num_objects() const { return static_cast<int>(measurement_of_object_.size()); }
  bool MeasurementFree(int i) const { return object_of_measurement_[static_cast<size_t>(i)] < 0; }
  bool ObjectFree(int j) const { return measurement_of_object_[static_cast<size_t>(j)] < 0; }
  bool PairFree(const Candidate& c) const {
    return MeasurementFree(c.measurement) && ObjectFree(c.object);
  }
  int ObjectOf(int i) const { return object_of_measurement_[static_cast<size_t>(i)]; }
  int MeasurementOf(int j) const { return measurement_of_object_[static_cast<size_t>(j)]; }
  // Per object, 1 when it got a measurement.
  std::vector<uint8_t> ObjectsMeasured() const {
    std::vector<uint8_t> measured(measurement_of_object_.size());
    for (size_t j = 0; j < measured.size(); ++j) measured[j] = measurement_of_object_[j] >= 0;
    return measured;
  }
  void Set(int i, int j);

 private:
  std::vector<int> object_of_measurement_;
  std::vector<int> measurement_of_object_;
};

// The scan the levels associate: its accepted measurements, its time, and which objects may
// update the state (per object index; update_budget.h).
struct ScanAssociation {
  const std::vector<PointMeasurement>& measurements;
  const std::vector<uint8_t>& may_update;
  int64_t utime = 0;
};

// Applies the free pairs of `pairs`, in their order, that pass gate_chi2 at the current state:
// assigns them, then updates the state with those whose object may update (in groups of
// options.update_group_size, ekf_update.h), and stamps those objects' last_update_utime. Counts
// the budget's skipped updates and the numerically unusable observations. Returns the number
// of observations that updated the state.
int ApplyPairs(const std::vector<Candidate>& pairs, double gate_chi2, const ScanAssociation& scan,
               const EstimatorOptions& options, ObservationPredictions* predicted,
               SlamState* state, Assignment* assignment, StepCounts* counts);

// Which field of a Candidate orders a greedy choice.
enum class PairOrder { kByNis, kByCost };

// Greedy one-to-one choice (global nearest neighbour, greedy): the pairs in increasing NIS or
// cost (ties keep their order), each taken when its measurement and object are free in `taken`
// and not yet chosen.
std::vector<Candidate> GreedyOneToOne(std::vector<Candidate> pairs, const Assignment& taken,
                                      PairOrder order);

}  // namespace slammtt
