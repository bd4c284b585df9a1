#include "perception/segmenter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angle.h"
#include "perception/centre_estimation.h"
#include "perception/trig_series.h"

namespace slammtt {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Beam::unusable_before of a beam without a usable return, before CountGapsAndDropDuplicates().
constexpr int32_t kMarker = -1;

// CCW angle from a to b, in [0, 2 pi), for angles already in (-pi, pi].
double CcwDelta(double a_rad, double b_rad) {
  const double d = b_rad - a_rad;
  return d < 0.0 ? d + kTwoPi : d;
}

const SegmenterOptions& Checked(const SegmenterOptions& options) {
  const std::string problem = CheckSegmenterOptions(options);
  if (!problem.empty()) throw std::invalid_argument("segmenter options: " + problem);
  return options;
}

}  // namespace

Segmenter::Segmenter(const SegmenterOptions& options)
    : options_(Checked(options)),
      criterion_(options.lambda_rad, options.sigma_r_m, options.max_beam_gap_rad) {}

const std::vector<Feature>& Segmenter::Segment(const ScanView& scan) {
  PrepareBeams(scan);
  FindClusters();
  return MakeFeatures();
}

void Segmenter::PrepareBeams(const ScanView& scan) {
  stats_ = SegmentationStats{};
  features_.clear();
  clusters_.clear();
  CollectBeams(scan);
  if (!beams_.empty()) {
    PutInCircularOrder();
    CountGapsAndDropDuplicates();
  }
  stats_.beams_used = static_cast<int64_t>(beams_.size());
}

const std::vector<Feature>& Segmenter::MakeFeatures() {
  features_.clear();
  stats_.clusters_too_few_points = 0;
  stats_.clusters_too_wide = 0;
  stats_.circle_fit_fallbacks = 0;
  for (const Cluster& cluster : clusters_) MakeFeature(cluster);
  std::sort(features_.begin(), features_.end(), [](const Feature& a, const Feature& b) {
    if (a.bearing_rad != b.bearing_rad) return a.bearing_rad < b.bearing_rad;
    return a.range_m < b.range_m;
  });
  stats_.features = static_cast<int64_t>(features_.size());
  return features_;
}

void Segmenter::CollectBeams(const ScanView& scan) {
  beams_.clear();
  const size_t n = (scan.angle_rad != nullptr && scan.range_m != nullptr) ? scan.num_beams : 0;
  stats_.beams = static_cast<int64_t>(scan.num_beams);
  // A sensor limit that is not a usable number is no limit; the options' limits always apply.
  double lo = options_.min_range_m;
  if (std::isfinite(scan.range_min_m) && scan.range_min_m > lo) lo = scan.range_min_m;
  double hi = options_.max_range_m;
  if (std::isfinite(scan.range_max_m) && scan.range_max_m > 0.0 && scan.range_max_m < hi) {
    hi = scan.range_max_m;
  }
  if (beams_.capacity() < n) beams_.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const double angle = scan.angle_rad[i];
    const double range = scan.range_m[i];
    const int32_t index = static_cast<int32_t>(i);
    // A beam without a usable return stays in the ring as a marker (when its direction is
    // known), so that the gap it leaves can be counted whatever order the beams come in.
    bool usable = false;
    if (scan.valid != nullptr && scan.valid[i] == 0) {
      ++stats_.beams_flagged_invalid;
    } else if (!std::isfinite(angle) || !std::isfinite(range)) {
      ++stats_.beams_non_finite;
    } else if (!(range > 0.0 && range >= lo && range <= hi)) {
      // A range of 0 is the sensor itself (RPLIDAR's "no return"), never a point of the world.
      ++stats_.beams_out_of_range;
    } else {
      usable = true;
    }
    if (!std::isfinite(angle)) continue;
    beams_.push_back(Beam{WrapAngle(angle), usable ? range : 0.0, index, usable ? 0 : kMarker});
  }
  if (n < scan.num_beams) stats_.beams_non_finite += static_cast<int64_t>(scan.num_beams - n);
}

void Segmenter::PutInCircularOrder() {
  const size_t m = beams_.size();
  size_t descents = 0;
  size_t ascents = 0;
  for (size_t k = 0; k + 1 < m; ++k) {
    descents += beams_[k + 1].angle_rad < beams_[k].angle_rad;
    ascents += beams_[k + 1].angle_rad > beams_[k].angle_rad;
  }
  // Mostly clockwise (the RPLIDAR turns clockwise seen from above): reverse first.
  if (descents > ascents) {
    std::reverse(beams_.begin(), beams_.end());
    std::swap(descents, ascents);
    stats_.beams_were_reversed = true;
  }
  // Sorted, or sorted after a rotation (one descent, and the end does not pass the start).
  if (descents == 0 || (descents == 1 && beams_[m - 1].angle_rad <= beams_[0].angle_rad)) return;
  stats_.beams_were_sorted = true;
  // Nearly sorted (RPLIDAR express mode: each sample's angle is corrected by up to 2 degrees,
  // so neighbours swap): start at the wrap, the largest drop, and insertion-sort, which costs
  // O(n + swaps). Anything far from sorted falls back to std::sort. Both give the one order of
  // the key (angle, input index).
  size_t wrap = 0;
  double largest_drop = 0.0;
  for (size_t k = 0; k + 1 < m; ++k) {
    const double drop = beams_[k].angle_rad - beams_[k + 1].angle_rad;
    if (drop > largest_drop) {
      largest_drop = drop;
      wrap = k + 1;
    }
  }
  std::rotate(beams_.begin(), beams_.begin() + static_cast<std::ptrdiff_t>(wrap), beams_.end());
  const auto before = [](const Beam& a, const Beam& b) {
    if (a.angle_rad != b.angle_rad) return a.angle_rad < b.angle_rad;
    return a.index < b.index;
  };
  const size_t max_moves = 4 * m;
  size_t moves = 0;
  for (size_t k = 1; k < m && moves <= max_moves; ++k) {
    const Beam beam = beams_[k];
    size_t j = k;
    while (j > 0 && before(beam, beams_[j - 1]) && moves <= max_moves) {
      beams_[j] = beams_[j - 1];
      --j;
      ++moves;
    }
    beams_[j] = beam;
  }
  if (moves > max_moves) std::sort(beams_.begin(), beams_.end(), before);
}

void Segmenter::CountGapsAndDropDuplicates() {
  const double tolerance = options_.duplicate_angle_tolerance_rad;
  size_t kept = 0;
  int32_t run = 0;  // markers since the last usable beam
  for (size_t k = 0; k < beams_.size(); ++k) {
    if (beams_[k].unusable_before == kMarker) {
      ++run;
      continue;
    }
    Beam beam = beams_[k];
    beam.unusable_before = run;
    run = 0;
    if (kept > 0 && CcwDelta(beams_[kept - 1].angle_rad, beam.angle_rad) < tolerance) {
      // The same direction twice: the nearer return stays, with the gap in front of the pair;
      // markers between the two (if any) count towards the next gap.
      const int32_t gap = beams_[kept - 1].unusable_before;
      if (beam.range_m < beams_[kept - 1].range_m) beams_[kept - 1] = beam;
      beams_[kept - 1].unusable_before = gap;
      run = beam.unusable_before;
      ++stats_.beams_duplicate;
    } else {
      beams_[kept++] = beam;
    }
  }
  // The ring is a circle: markers after the last usable beam lie before the first one...
  if (kept > 0) beams_[0].unusable_before += run;
  // ...and the last and the first beam are neighbours.
  while (kept > 1 && CcwDelta(beams_[kept - 1].angle_rad, beams_[0].angle_rad) < tolerance) {
    const Beam last = beams_[kept - 1];
    const int32_t gap = last.unusable_before + beams_[0].unusable_before;
    if (last.range_m < beams_[0].range_m) beams_[0] = last;
    beams_[0].unusable_before = gap;
    --kept;
    ++stats_.beams_duplicate;
  }
  beams_.resize(kept);
}

void Segmenter::FindClusters() {
  clusters_.clear();
  const size_t m = beams_.size();
  if (m == 0) return;
  if (m == 1) {
    clusters_.push_back(Cluster{0, 1});
    stats_.clusters = 1;
    return;
  }
  if (splits_.size() < m) splits_.resize(m);
  size_t first_split = m;
  for (size_t k = 0; k < m; ++k) {
    const Beam& a = beams_[k];
    const Beam& b = beams_[k + 1 < m ? k + 1 : 0];
    const bool split = b.unusable_before > options_.max_dropped_beams ||
                       criterion_.Splits(a.range_m, b.range_m, CcwDelta(a.angle_rad, b.angle_rad));
    splits_[k] = split;
    if (split && first_split == m) first_split = k;
  }
  if (first_split == m) {  // one closed cluster around the sensor
    clusters_.push_back(Cluster{0, m});
  } else {
    size_t cluster_start = first_split + 1 < m ? first_split + 1 : 0;
    size_t count = 0;
    size_t k = cluster_start;
    for (size_t step = 0; step < m; ++step) {
      ++count;
      if (splits_[k]) {
        clusters_.push_back(Cluster{cluster_start, count});
        cluster_start = k + 1 < m ? k + 1 : 0;
        count = 0;
      }
      k = k + 1 < m ? k + 1 : 0;
    }
  }
  stats_.clusters = static_cast<int64_t>(clusters_.size());
  for (const Cluster& c : clusters_) {
    if (c.ring_start + c.count > m || (c.count == m && m > 1)) ++stats_.clusters_across_seam;
  }
}

void Segmenter::MakeFeature(const Cluster& c) {
  const size_t ring_start = c.ring_start;
  const size_t count = c.count;
  const size_t m = beams_.size();
  if (count < static_cast<size_t>(options_.min_points)) {
    ++stats_.clusters_too_few_points;
    return;
  }
  if (bearing_.size() < count) {
    bearing_.resize(count);
    range_.resize(count);
    x_.resize(count);
    y_.resize(count);
  }
  size_t k = ring_start;
  double bearing = beams_[k].angle_rad;
  for (size_t i = 0; i < count; ++i) {
    if (i > 0) {
      const size_t next = k + 1 < m ? k + 1 : 0;
      bearing += CcwDelta(beams_[k].angle_rad, beams_[next].angle_rad);
      k = next;
    }
    bearing_[i] = bearing;
    range_[i] = beams_[k].range_m;
  }
  const size_t last_ring_index = k;
  const double extent = bearing_[count - 1] - bearing_[0];
  if (extent >= M_PI) {  // surrounds the sensor or spans a half plane: no centre
    ++stats_.clusters_too_wide;
    return;
  }
  // First-to-last distance by the law of cosines, before any per-point trigonometry: most beams
  // of an indoor scan are on walls, which stop here.
  const double r_first = range_[0];
  const double r_last = range_[count - 1];
  const double width = std::sqrt(std::max(
      0.0, r_first * r_first + r_last * r_last - 2.0 * r_first * r_last * std::cos(extent)));
  if (width > options_.max_width_m) {
    ++stats_.clusters_too_wide;
    return;
  }
  // The centre rules are rotation invariant: work in a frame turned to the middle point's
  // bearing, where every point is within pi of the x axis and trig_series.h applies.
  const double reference_bearing = bearing_[count / 2];
  for (size_t i = 0; i < count; ++i) {
    bearing_[i] -= reference_bearing;
    double sin_b = 0.0;
    double cos_b = 0.0;
    SinCosSeries(bearing_[i], &sin_b, &cos_b);
    x_[i] = range_[i] * cos_b;
    y_[i] = range_[i] * sin_b;
  }

  const double spacing = count > 1 ? extent / static_cast<double>(count - 1) : 0.0;
  ClusterView cluster;
  cluster.bearing_rad = bearing_.data();
  cluster.range_m = range_.data();
  cluster.x_m = x_.data();
  cluster.y_m = y_.data();
  cluster.count = count;
  if (count < m && count > 1) {
    // An edge is occluded when the adjacent beam outside it (within 1.5 spacings) is nearer.
    const Beam& before = beams_[ring_start > 0 ? ring_start - 1 : m - 1];
    const Beam& after = beams_[last_ring_index + 1 < m ? last_ring_index + 1 : 0];
    const double adjacent = 1.5 * spacing;
    cluster.first_edge_occluded =
        before.range_m < range_[0] &&
        CcwDelta(before.angle_rad, beams_[ring_start].angle_rad) <= adjacent;
    cluster.last_edge_occluded =
        after.range_m < range_[count - 1] &&
        CcwDelta(beams_[last_ring_index].angle_rad, after.angle_rad) <= adjacent;
  }
  const CentreEstimate corrected = RadiusCorrectedCentre(cluster, options_.max_object_radius_m);
  CentreEstimate centre = corrected;
  double offset_var = 0.0;  // variance of a known, uncorrected offset of the centre
  switch (options_.centre_rule) {
    case CentreRule::kMiddlePoint:
      centre = MiddlePointCentre(cluster);
      offset_var = corrected.radius_m * corrected.radius_m;
      break;
    case CentreRule::kRadiusCorrected:
      break;
    case CentreRule::kCircleFit:
      centre = CircleFitCentre(cluster, options_.max_object_radius_m, options_.sigma_r_m);
      if (centre.fell_back) ++stats_.circle_fit_fallbacks;
      break;
  }
  if (!std::isfinite(centre.range_m) || !(centre.range_m > 0.0) ||
      !std::isfinite(centre.bearing_rad)) {
    // Not reachable with finite positive ranges; a guard so that no NaN ever leaves here.
    centre = MiddlePointCentre(cluster);
  }

  // The object's size for the shape terms: the rule's own radius estimate, or the extent's.
  const double radius = centre.radius_m > 0.0 ? centre.radius_m : corrected.radius_m;
  const double f = options_.shape_sigma_fraction;
  const double lateral = f * radius / centre.range_m;
  Feature feature;
  feature.range_m = centre.range_m;
  feature.bearing_rad = WrapAngle(reference_bearing + centre.bearing_rad);
  feature.width_m = width;
  feature.num_points = static_cast<int>(count);
  feature.radius_m = centre.radius_m;
  feature.covariance(0, 0) =
      options_.sigma_r_m * options_.sigma_r_m + f * f * radius * radius + offset_var;
  feature.covariance(1, 1) = options_.bearing_sigma_rad * options_.bearing_sigma_rad +
                             spacing * spacing / 24.0 + lateral * lateral;
  feature.covariance(0, 1) = 0.0;
  feature.covariance(1, 0) = 0.0;
  feature.first_beam_index = beams_[ring_start].index;
  feature.last_beam_index = beams_[last_ring_index].index;
  features_.push_back(feature);
}

std::vector<Feature> SegmentScan(const ScanView& scan, const SegmenterOptions& options) {
  Segmenter segmenter(options);
  return segmenter.Segment(scan);
}

}  // namespace slammtt
