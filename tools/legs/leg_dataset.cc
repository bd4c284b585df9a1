#include "tools/legs/leg_dataset.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_map>

namespace slammtt {
namespace {

constexpr double kCellM = 0.1;

int64_t CellKey(int64_t ix, int64_t iy) { return (ix << 32) ^ (iy & 0xffffffff); }

int64_t CellIndex(double v) { return static_cast<int64_t>(std::floor(v / kCellM)); }

}  // namespace

ScanView RecordedScan::view() const {
  ScanView v = MakeScanView(angle_rad, range_m, valid);
  v.range_min_m = range_min_m;
  v.range_max_m = range_max_m;
  return v;
}

RecordedScan Decimate(const RecordedScan& scan, int stride) {
  if (stride <= 1) return scan;
  RecordedScan out;
  out.utime = scan.utime;
  out.range_min_m = scan.range_min_m;
  out.range_max_m = scan.range_max_m;
  out.labelled = scan.labelled;
  out.labels_m = scan.labels_m;
  const size_t s = static_cast<size_t>(stride);
  for (size_t i = 0; i < scan.angle_rad.size(); i += s) {
    out.angle_rad.push_back(scan.angle_rad[i]);
    out.range_m.push_back(scan.range_m[i]);
    if (i < scan.valid.size()) out.valid.push_back(scan.valid[i]);
  }
  return out;
}

bool LabelArc::Contains(double x_m, double y_m) const {
  const double bearing = std::atan2(y_m, x_m) * 180.0 / M_PI;
  return bearing > min_bearing_deg && bearing < max_bearing_deg &&
         std::hypot(x_m, y_m) < max_range_m;
}

StaticBackground::StaticBackground(const std::vector<RecordedScan>& scans) {
  std::unordered_map<int64_t, int64_t> hits;
  std::vector<int64_t> cells;
  for (const RecordedScan& scan : scans) {
    cells.clear();
    for (size_t i = 0; i < scan.range_m.size() && i < scan.angle_rad.size(); ++i) {
      if (i < scan.valid.size() && scan.valid[i] == 0) continue;
      const double r = scan.range_m[i];
      const double a = scan.angle_rad[i];
      if (!std::isfinite(r) || !std::isfinite(a) || !(r > 0.0)) continue;
      cells.push_back(CellKey(CellIndex(r * std::cos(a)), CellIndex(r * std::sin(a))));
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    for (int64_t key : cells) ++hits[key];
  }
  const auto needed = static_cast<int64_t>(scans.size() + 1) / 2;
  for (const auto& [key, count] : hits) {
    if (count >= needed) keys_.push_back(key);
  }
  std::sort(keys_.begin(), keys_.end());
}

bool StaticBackground::Contains(double x_m, double y_m) const {
  const int64_t ix = CellIndex(x_m);
  const int64_t iy = CellIndex(y_m);
  for (int64_t dx = -1; dx <= 1; ++dx) {
    for (int64_t dy = -1; dy <= 1; ++dy) {
      if (std::binary_search(keys_.begin(), keys_.end(), CellKey(ix + dx, iy + dy))) return true;
    }
  }
  return false;
}

ClusterTruth ClassifyCluster(const LegClusterRecord& record,
                             const std::vector<Eigen::Vector2d>& labels,
                             const StaticBackground* background) {
  const Eigen::Vector2d c(record.centroid_x_m, record.centroid_y_m);
  for (const Eigen::Vector2d& label : labels) {
    if ((label - c).norm() <= kLabelMatchM) return ClusterTruth::kLeg;
  }
  if (background != nullptr && background->Contains(c.x(), c.y())) {
    return ClusterTruth::kBackground;
  }
  return ClusterTruth::kUnknown;
}

ClusterTruth ClassifySimulatedCluster(const LegClusterRecord& record, const RecordedScan& scan) {
  const Eigen::Vector2d c(record.centroid_x_m, record.centroid_y_m);
  for (const Eigen::Vector2d& leg : scan.labels_m) {
    if ((leg - c).norm() <= kLabelMatchM) return ClusterTruth::kLeg;
  }
  for (const Eigen::Vector2d& p : scan.people_m) {
    if ((p - c).norm() <= kSimulatedClearM) return ClusterTruth::kUnknown;
  }
  return ClusterTruth::kBackground;
}

double LegDetectionScore::recall() const {
  return labels > 0 ? static_cast<double>(labels_found) / static_cast<double>(labels)
                    : std::numeric_limits<double>::quiet_NaN();
}

double LegDetectionScore::person_leg_recall() const {
  return labels > 0 ? static_cast<double>(labels_in_people) / static_cast<double>(labels)
                    : std::numeric_limits<double>::quiet_NaN();
}

double LegDetectionScore::precision() const {
  return candidates_in_arc > 0
             ? static_cast<double>(candidates_matched) / static_cast<double>(candidates_in_arc)
             : std::numeric_limits<double>::quiet_NaN();
}

double LegDetectionScore::people_per_scan() const {
  return scans > 0 ? static_cast<double>(people) / static_cast<double>(scans)
                   : std::numeric_limits<double>::quiet_NaN();
}

double LegDetectionScore::people_per_minute() const {
  const double minutes = static_cast<double>(last_utime - first_utime) / 6e7;
  return minutes > 0.0 ? static_cast<double>(people) / minutes
                       : std::numeric_limits<double>::quiet_NaN();
}

void ScoreScan(const RecordedScan& scan, const Segmenter& segmenter, double leg_threshold,
               const LabelArc& arc, LegDetectionScore* score) {
  if (score->scans == 0) score->first_utime = scan.utime;
  score->last_utime = scan.utime;
  ++score->scans;
  const auto people = static_cast<int64_t>(segmenter.people().size());
  score->people += people;
  for (const PersonFeature& p : segmenter.people()) score->people_one_leg += p.num_legs == 1;
  constexpr size_t kHistogram = 6;
  score->people_per_scan_histogram.resize(kHistogram, 0);
  ++score->people_per_scan_histogram[std::min<size_t>(static_cast<size_t>(people),
                                                      kHistogram - 1)];
  if (!scan.labelled) return;
  std::vector<Eigen::Vector2d> candidates;
  for (const Feature& f : segmenter.features()) {
    if (f.leg_likeness < leg_threshold || f.leg_cluster < 0) continue;
    const LegClusterRecord& r = segmenter.leg_clusters()[static_cast<size_t>(f.leg_cluster)];
    candidates.emplace_back(r.centroid_x_m, r.centroid_y_m);
  }
  // One-to-one, nearest pairs first (ties: lower indices).
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = 0; j < scan.labels_m.size(); ++j) {
      const double d = (candidates[i] - scan.labels_m[j]).norm();
      if (d <= kLabelMatchM) pairs.emplace_back(d, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<uint8_t> used_candidate(candidates.size(), 0);
  std::vector<uint8_t> used_label(scan.labels_m.size(), 0);
  int64_t matched = 0;
  for (const auto& [d, i, j] : pairs) {
    if (used_candidate[i] || used_label[j]) continue;
    used_candidate[i] = 1;
    used_label[j] = 1;
    ++matched;
  }
  score->labels += static_cast<int64_t>(scan.labels_m.size());
  score->labels_found += matched;
  // The labels that a person feature stands on: what reaches the tracker as a person.
  for (const Eigen::Vector2d& label : scan.labels_m) {
    bool in_person = false;
    for (const PersonFeature& p : segmenter.people()) {
      for (int k = 0; k < p.num_legs && !in_person; ++k) {
        const Feature& f = segmenter.features()[static_cast<size_t>(p.leg_index[k])];
        if (f.leg_cluster < 0) continue;
        const LegClusterRecord& r = segmenter.leg_clusters()[static_cast<size_t>(f.leg_cluster)];
        const Eigen::Vector2d centroid(r.centroid_x_m, r.centroid_y_m);
        in_person = (centroid - label).norm() <= kLabelMatchM;
      }
    }
    score->labels_in_people += in_person;
  }
  // A candidate is a leg when a label lies within kLabelMatchM (ClassifyCluster's rule), matched
  // one-to-one or not: two legs that leg_tracker's clustering joined into one labelled cluster
  // are two legs.
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!arc.Contains(candidates[i].x(), candidates[i].y())) continue;
    ++score->candidates_in_arc;
    bool leg = used_candidate[i] != 0;
    for (size_t j = 0; j < scan.labels_m.size() && !leg; ++j) {
      leg = (candidates[i] - scan.labels_m[j]).norm() <= kLabelMatchM;
    }
    score->candidates_matched += leg;
  }
}

}  // namespace slammtt
