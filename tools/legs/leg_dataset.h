// The leg_tracker recordings as training and test data for the leg classifier: which clusters
// are legs, which are surely not, and the detection figures against the labels.
//
// The labels (`/leg_cluster_positions` of leg_tracker's `positive_N_extracted.bag`, imported
// as LEG_LABELS) were made automatically by leg_tracker's extract_positive_training_clusters
// (launch/training/extract_positive_training_clusters_res=0.33.launch): every cluster of its
// own clustering (0.13 m jump, at least 3 points) whose centroid lies in the arc of bearings
// (-15, 15) degrees ((-15, 10) for positive_4) and ranges below 5 m is a leg, and its centroid
// is the label. So:
//  - a label is a leg's cluster centroid, not a person; a cluster of ours is a leg when a label
//    lies within kLabelMatchM of its centroid;
//  - outside the arc nothing is labelled, and people do walk there (to and from the arc): a
//    cluster outside the arc is not known to be a non-leg. Detection precision is therefore
//    measured inside the arc only (LabelArc), where every leg is labelled, and the people
//    found in a recording where nobody is present (negative_2) measure false people directly;
//  - negatives for training are the clusters that belong to the static background of a
//    recording made by a scanner that stands still (StaticBackground): an object hit at the
//    same place in at least half of the recording's scans is not a walking person.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "perception/segmenter.h"

namespace slammtt {

// A cluster whose centroid is within this of a label is a leg [m]. Our clusters and
// leg_tracker's differ at their edges (eq. 15 vs a fixed 0.13 m jump): on positive_4, of the
// labels with a cluster of ours within 0.2 m, 82 % have one within 0.05 m, 95 % within 0.1 m,
// 99 % within 0.15 m; and where leg_tracker's 0.13 m jump joined two legs into one cluster
// (one label between the legs) ours are two, each 0.1-0.2 m from that label.
inline constexpr double kLabelMatchM = 0.2;

// One scan as the stack's laser_scan_t carries it, and its labels (if the log has any).
struct RecordedScan {
  int64_t utime = 0;
  std::vector<float> angle_rad;
  std::vector<float> range_m;
  std::vector<int8_t> valid;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  bool labelled = false;
  std::vector<Eigen::Vector2d> labels_m;  // sensor frame
  // Simulated scans only: where every person and leg is (seen or not), sensor frame. A cluster
  // near none of them is surely not a leg.
  std::vector<Eigen::Vector2d> people_m;
  ScanView view() const;
};

// Every `stride`-th beam of `scan` (beams 0, stride, 2 stride, ...): the same surfaces seen by
// a scanner with `stride` times the angular spacing (0.35 degrees x 2, x 3: 0.70 and 1.05
// degrees, around the RPLIDAR A2's 0.9). Labels are kept.
RecordedScan Decimate(const RecordedScan& scan, int stride);

// Where the labeller labelled every leg: bearings (min, max) degrees, ranges below max_range_m.
struct LabelArc {
  double min_bearing_deg = -15.0;
  double max_bearing_deg = 15.0;
  double max_range_m = 5.0;
  bool Contains(double x_m, double y_m) const;
};

// Hits of valid returns per 0.1 m cell over every scan of a recording of a standing scanner.
class StaticBackground {
 public:
  explicit StaticBackground(const std::vector<RecordedScan>& scans);
  // The cell of (x, y) or one of its 8 neighbours was hit in at least half of the scans.
  bool Contains(double x_m, double y_m) const;

 private:
  std::vector<int64_t> keys_;    // sorted cell keys of the cells hit that often
};

enum class ClusterTruth { kLeg, kBackground, kUnknown };

// kLeg: a label within kLabelMatchM of the centroid; kBackground: otherwise, when the centroid
// is static background (and `background` is not null); kUnknown otherwise.
ClusterTruth ClassifyCluster(const LegClusterRecord& record,
                             const std::vector<Eigen::Vector2d>& labels,
                             const StaticBackground* background);

// A cluster of a simulated scan: kLeg when a leg (labels_m) is within kLabelMatchM of its
// centroid, kBackground when no person or leg (people_m) is within kSimulatedClearM, else
// kUnknown.
inline constexpr double kSimulatedClearM = 0.5;
ClusterTruth ClassifySimulatedCluster(const LegClusterRecord& record, const RecordedScan& scan);

// Detection figures of one recording, accumulated scan by scan.
struct LegDetectionScore {
  int64_t scans = 0;
  int64_t labels = 0;             // labels of the labelled scans
  int64_t labels_found = 0;       // matched one-to-one by a leg candidate within kLabelMatchM
  int64_t labels_in_people = 0;   // within kLabelMatchM of a leg of a person feature
  int64_t candidates_in_arc = 0;  // leg candidates whose centroid is inside the arc
  int64_t candidates_matched = 0; // ...within kLabelMatchM of a label (legs, ClassifyCluster)
  int64_t people = 0;
  int64_t people_one_leg = 0;
  std::vector<int64_t> people_per_scan_histogram;  // [k]: scans with k people (last: k or more)
  int64_t first_utime = 0;
  int64_t last_utime = 0;
  double recall() const;
  double person_leg_recall() const;  // labels_in_people / labels
  double precision() const;
  double people_per_scan() const;
  double people_per_minute() const;
};

// Adds one segmented scan: leg candidates are the segmenter's point features with
// leg_likeness >= leg_threshold (matched through their cluster's centroid).
void ScoreScan(const RecordedScan& scan, const Segmenter& segmenter, double leg_threshold,
               const LabelArc& arc, LegDetectionScore* score);

}  // namespace slammtt
