#include "perception/segmenter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/angle.h"
#include "common/checked_options.h"
#include <Eigen/Dense>

#include "perception/centre_estimation.h"
#include "perception/leg_likeness.h"
#include "perception/trig_series.h"

namespace slammtt {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Beam::unusable_before of a beam without a usable return, before CountGapsAndDropDuplicates().
constexpr int32_t kMarker = -1;
// A compact cluster with straight runs is a round object when one circle (3 parameters) fits
// it about as well as its runs (2 per run): with two runs or more, when the circle's RMS
// residual is at most 1.1 times the runs' pooled RMS (the simpler model wins; chords of a
// large disc are as good as the circle only when the noise hides their sagitta); with one run,
// when it is at most 0.7 times the run's (on a straight surface the circle only fits noise
// and its RMS is sqrt((n - 3) / (n - 2)) of the line's, 0.82 or more for five points or more).
constexpr double kRoundRmsRatioRuns = 1.1;
constexpr double kRoundRmsRatioOneRun = 0.7;
// A leg candidate with a convexity (leg_features.h) below this is flat: a half circle, what a
// leg shows, gives about 0.7, a flat surface 0 (plus noise).
constexpr double kFlatConvexity = 0.1;
// A leg-like cluster of more than three points is a piece of a line of the scan when every
// point lies within this distance of the line. A leg is round: seen over four beams or more,
// its outline (radius 0.03-0.1 m) departs from a straight line by a good part of its radius,
// more than this plus the range noise. Measured on the world's scenes (docs/perception.md,
// "World scenarios"): 1 of 3670 leg candidates on real legs came this close to a line, against
// 103 of the false people's legs, on the stubs of walls beside openings and furniture sides.
constexpr double kOnSurfaceM = 0.025;
// Pieces in a run of clusters separated only by beams without a return (FindDropoutRuns) that
// make a surface: two are too often a person's two legs with no return around them (the
// background out of range, or blanked in the extracted leg_tracker bags: with two, positive_4's
// labelled legs in a person fell from 0.80 to 0.66); a wall that drops beams gives many.
constexpr size_t kMinDropoutRun = 3;
// Lines of neighbouring clusters are tried for one line only when their normals are this close.
constexpr double kMergeAngleRad = 5.0 * M_PI / 180.0;

// CCW angle from a to b, in [0, 2 pi), for angles already in (-pi, pi].
double CcwDelta(double a_rad, double b_rad) {
  const double d = b_rad - a_rad;
  return d < 0.0 ? d + kTwoPi : d;
}

// Distance from `point` (sensor frame) to the nearest line feature (its observed extent) that
// it lies in front of, on the sensor's side of the line; +infinity without one.
double SurfaceClearance(const Eigen::Vector2d& point, const std::vector<LineFeature>& lines) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const LineFeature& line : lines) {
    const Eigen::Vector2d normal(std::cos(line.alpha_rad), std::sin(line.alpha_rad));
    if (line.rho_m - point.dot(normal) <= 0.0) continue;  // on the line or beyond it
    const Eigen::Vector2d extent = line.last_point_m - line.first_point_m;
    const double length2 = extent.squaredNorm();
    const double t =
        length2 > 0.0 ? std::clamp((point - line.first_point_m).dot(extent) / length2, 0.0, 1.0)
                      : 0.0;
    clearance = std::min(clearance, (line.first_point_m + t * extent - point).norm());
  }
  return clearance;
}

}  // namespace

Segmenter::Segmenter(const SegmenterOptions& options)
    : options_(CheckedOptions(options, &CheckSegmenterOptions, "segmenter options")),
      criterion_(options.lambda_rad, options.sigma_r_m, options.max_beam_gap_rad),
      leg_model_(options.leg_model != nullptr ? options.leg_model : &TrainedLegModel()) {
  const char* problem = CheckLegModel(*leg_model_);
  if (*problem != '\0') throw std::invalid_argument(std::string("segmenter options: ") + problem);
}

const std::vector<Feature>& Segmenter::Segment(const ScanView& scan) {
  PrepareBeams(scan);
  FindClusters();
  ExtractLines();
  MakeFeatures();
  return FindPeople();
}

void Segmenter::PrepareBeams(const ScanView& scan) {
  stats_ = SegmentationStats{};
  features_.clear();
  provisional_.clear();
  lines_.clear();
  people_.clear();
  leg_clusters_.clear();
  clusters_.clear();
  structure_.clear();
  CollectBeams(scan);
  if (!beams_.empty()) {
    PutInCircularOrder();
    CountGapsAndDropDuplicates();
  }
  stats_.beams_used = static_cast<int64_t>(beams_.size());
}

void Segmenter::MakeFeatures() {
  features_.clear();
  provisional_.clear();
  leg_clusters_.clear();
  stats_.clusters_too_few_points = 0;
  stats_.clusters_too_wide = 0;
  stats_.circle_fit_fallbacks = 0;
  stats_.beams_mixed_pixel = 0;
  stats_.beams_isolated = 0;
  stats_.clusters_on_lines = 0;
  stats_.clusters_structure_pieces = 0;
  stats_.provisional_legs = 0;
  const bool have_structure = structure_.size() == clusters_.size();
  for (size_t c = 0; c < clusters_.size(); ++c) {
    if (have_structure && structure_[c]) continue;
    MakeFeature(clusters_[c]);
  }
  const auto by_bearing = [](const Feature& a, const Feature& b) {
    if (a.bearing_rad != b.bearing_rad) return a.bearing_rad < b.bearing_rad;
    return a.range_m < b.range_m;
  };
  std::sort(features_.begin(), features_.end(), by_bearing);
  std::sort(provisional_.begin(), provisional_.end(), by_bearing);
  stats_.features = static_cast<int64_t>(features_.size());
  stats_.provisional_legs = static_cast<int64_t>(provisional_.size());
}

const std::vector<Feature>& Segmenter::FindPeople() {
  people_.clear();
  stats_.leg_candidates = 0;
  stats_.provisional_legs_used = 0;
  stats_.leg_stubs = 0;
  stats_.people = 0;
  stats_.people_one_leg = 0;
  if (!options_.detect_people) return features_;
  candidates_.clear();
  const auto add = [this](const Feature& f, bool provisional, int32_t index) {
    LegCandidate c;
    c.range_m = f.range_m;
    c.bearing_rad = f.bearing_rad;
    c.covariance = f.covariance;
    c.leg_likeness = f.leg_likeness;
    c.provisional = provisional;
    c.open_edges = 2 - f.bounded_edges;
    c.num_points = f.num_points;
    // Only its rule reads it (off by default): not worth a pass over the lines per candidate.
    if (options_.person.single_leg_surface_clearance_m > 0.0) {
      c.surface_clearance_m =
          SurfaceClearance(f.range_m * Eigen::Vector2d(std::cos(f.bearing_rad),
                                                       std::sin(f.bearing_rad)),
                           lines_);
    }
    // Flat (a leg, round, shows about 0.7: leg_features.h), with both edges unbounded.
    if (f.bounded_edges == 0 && f.leg_cluster >= 0) {
      const LegClusterRecord& r = leg_clusters_[static_cast<size_t>(f.leg_cluster)];
      c.surface_piece = static_cast<double>(r.features[kConvexity]) < kFlatConvexity;
    }
    c.feature_index = index;
    candidates_.push_back(c);
  };
  for (size_t i = 0; i < features_.size(); ++i) {
    if (features_[i].leg_likeness >= options_.leg_threshold) {
      add(features_[i], false, static_cast<int32_t>(i));
    }
  }
  stats_.leg_candidates = static_cast<int64_t>(candidates_.size());
  // Provisional legs get the codes -2, -3, ... until they have a place among the features.
  for (size_t j = 0; j < provisional_.size(); ++j) add(provisional_[j], true, -2 - int32_t(j));
  if (options_.person.separate_dropout_pieces) FindDropoutRuns();
  person_detector_.Detect(candidates_, options_.person, &people_, &candidate_used_,
                          SightLinesOfScan());
  for (const PersonFeature& p : people_) stats_.people_one_leg += p.num_legs == 1;
  stats_.people = static_cast<int64_t>(people_.size());
  // Provisional legs that joined a person become point features, in bearing order.
  const size_t n = features_.size();
  const size_t first_provisional_candidate = static_cast<size_t>(stats_.leg_candidates);
  size_t used = 0;
  for (size_t k = first_provisional_candidate; k < candidates_.size(); ++k) {
    used += candidate_used_[k] != 0;
  }
  stats_.provisional_legs_used = static_cast<int64_t>(used);
  // Stubs (PersonDetector::Detect's kStubLeg) leave the point features: too leg-like to be a
  // landmark, too short of their extent to be a person (person_detection.h).
  dropped_.assign(n, 0);
  size_t stubs = 0;
  for (size_t k = 0; k < first_provisional_candidate; ++k) {
    if (candidate_used_[k] != kStubLeg) continue;
    dropped_[static_cast<size_t>(candidates_[k].feature_index)] = 1;
    ++stubs;
  }
  stats_.leg_stubs = static_cast<int64_t>(stubs);
  if (used == 0 && stubs == 0) return features_;
  // final_index_[old]: position in the merged list of feature `old` (features_ first, then
  // provisional_); -1 for a provisional leg or a stub that is dropped.
  final_index_.assign(n + provisional_.size(), -1);
  merged_.clear();
  size_t next_provisional = 0;
  size_t i = 0;
  while (i < n || next_provisional < provisional_.size()) {
    // Skip provisional legs that no person uses.
    while (next_provisional < provisional_.size() &&
           !candidate_used_[first_provisional_candidate + next_provisional]) {
      ++next_provisional;
    }
    const bool take_provisional =
        next_provisional < provisional_.size() &&
        (i >= n || provisional_[next_provisional].bearing_rad < features_[i].bearing_rad);
    if (take_provisional) {
      final_index_[n + next_provisional] = static_cast<int32_t>(merged_.size());
      merged_.push_back(provisional_[next_provisional++]);
    } else if (i < n) {
      if (!dropped_[i]) {
        final_index_[i] = static_cast<int32_t>(merged_.size());
        merged_.push_back(features_[i]);
      }
      ++i;
    } else {
      break;
    }
  }
  for (PersonFeature& p : people_) {
    for (int32_t& leg : p.leg_index) {
      if (leg >= 0) {
        leg = final_index_[static_cast<size_t>(leg)];
      } else if (leg <= -2) {
        leg = final_index_[n + static_cast<size_t>(-2 - leg)];
      }
    }
  }
  features_.swap(merged_);
  stats_.features = static_cast<int64_t>(features_.size());
  return features_;
}

void Segmenter::FindDropoutRuns() {
  // The point features and the provisional legs as one list of pieces: i < n is features_[i],
  // the others provisional_[i - n]. A piece's successor is the piece whose first beam is the
  // next usable beam after its last one, when both have no usable return on either side.
  int32_t max_index = -1;
  for (const Beam& b : beams_) max_index = std::max(max_index, b.index);
  ring_of_input_.assign(static_cast<size_t>(max_index + 1), -1);
  for (size_t k = 0; k < beams_.size(); ++k) {
    ring_of_input_[static_cast<size_t>(beams_[k].index)] = static_cast<int32_t>(k);
  }
  const size_t n = features_.size();
  const size_t total = n + provisional_.size();
  const auto piece = [&](size_t i) -> const Feature& {
    return i < n ? features_[i] : provisional_[i - n];
  };
  const auto ring = [&](int32_t input_index) {
    return static_cast<size_t>(ring_of_input_[static_cast<size_t>(input_index)]);
  };
  piece_at_ring_.assign(beams_.size(), -1);
  for (size_t i = 0; i < total; ++i) {
    piece_at_ring_[ring(piece(i).first_beam_index)] = static_cast<int32_t>(i);
  }
  piece_next_.assign(total, -1);
  piece_has_previous_.assign(total, 0);
  piece_run_.assign(total, -1);
  for (size_t i = 0; i < total; ++i) {
    if (piece(i).bounded_edges != 0) continue;
    const int32_t j = piece_at_ring_[Next(ring(piece(i).last_beam_index))];
    if (j < 0 || static_cast<size_t>(j) == i || piece(static_cast<size_t>(j)).bounded_edges != 0) {
      continue;
    }
    piece_next_[i] = j;
    piece_has_previous_[static_cast<size_t>(j)] = 1;
  }
  // Each run is labelled by its first piece; a run around the whole ring by any of its own.
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < total; ++i) {
      if (piece_next_[i] < 0 || piece_run_[i] >= 0) continue;
      if (pass == 0 && piece_has_previous_[i]) continue;
      for (int32_t k = static_cast<int32_t>(i); k >= 0 && piece_run_[size_t(k)] < 0;
           k = piece_next_[size_t(k)]) {
        piece_run_[size_t(k)] = static_cast<int32_t>(i);
      }
    }
  }
  // A run is a surface when it has kMinDropoutRun pieces or more and one straight line holds
  // all their points (within the split distance, as a line of the scan).
  for (size_t head = 0; head < total; ++head) {
    if (piece_run_[head] != static_cast<int32_t>(head)) continue;
    size_t pieces = 0;
    size_t count = 0;
    for (size_t i = 0; i < total; ++i) {
      if (piece_run_[i] != static_cast<int32_t>(head)) continue;
      const size_t first = ring(piece(i).first_beam_index);
      const size_t last = ring(piece(i).last_beam_index);
      const size_t points = (last + beams_.size() - first) % beams_.size() + 1;
      FillRunPoints(first, points, count);
      count += points;
      ++pieces;
    }
    bool surface = pieces >= kMinDropoutRun && count >= 2;
    if (surface) {
      const LineFit fit = FitLine(sensor_x_.data(), sensor_y_.data(), count, options_.sigma_r_m,
                                  options_.bearing_sigma_rad);
      const double ca = std::cos(fit.alpha_rad);
      const double sa = std::sin(fit.alpha_rad);
      const double tolerance = SplitDistance(MeanRange(count));
      for (size_t i = 0; i < count && surface; ++i) {
        surface = std::abs(DistanceFromLine(fit.rho_m, ca, sa, sensor_x_[i], sensor_y_[i])) <=
                  tolerance;
      }
    }
    if (surface) continue;
    for (size_t i = 0; i < total; ++i) {
      if (piece_run_[i] == static_cast<int32_t>(head)) piece_run_[i] = -1;
    }
  }
  for (LegCandidate& c : candidates_) {
    const size_t i = c.feature_index >= 0 ? static_cast<size_t>(c.feature_index)
                                          : n + static_cast<size_t>(-2 - c.feature_index);
    c.dropout_run = piece_run_[i];
  }
}

const SightLines* Segmenter::SightLinesOfScan() {
  if (!options_.person.hidden_leg_centre) return nullptr;
  // The ring is in circular order: it starts anywhere. Copy it from its smallest angle on.
  const size_t m = beams_.size();
  size_t first = 0;
  for (size_t k = 1; k < m; ++k) {
    if (beams_[k].angle_rad < beams_[first].angle_rad) first = k;
  }
  sight_angle_.resize(m);
  sight_range_.resize(m);
  for (size_t i = 0, k = first; i < m; ++i, k = Next(k)) {
    sight_angle_[i] = beams_[k].angle_rad;
    sight_range_[i] = beams_[k].range_m;
  }
  sight_.angle_rad = sight_angle_.data();
  sight_.range_m = sight_range_.data();
  sight_.count = m;
  sight_.max_gap_rad = options_.max_beam_gap_rad;
  return &sight_;
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
  // Beyond the cap, every k-th beam (segmenter.h, step 0).
  const size_t cap = static_cast<size_t>(options_.max_beams_per_scan);
  const size_t stride = n > cap ? (n + cap - 1) / cap : 1;
  stats_.beams_over_cap = static_cast<int64_t>(n - (n + stride - 1) / stride);
  if (beams_.capacity() < std::min(n, cap)) beams_.reserve(std::min(n, cap));
  for (size_t i = 0; i < n; i += stride) {
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
  CountDepthEdges();
}

void Segmenter::CountDepthEdges() {
  stats_.depth_edges = 0;
  const size_t m = beams_.size();
  if (m < 2) return;
  // Neighbours: no unusable beam between them and closer than the gap bound.
  const auto adjacent = [this](size_t a, size_t b) {
    return beams_[b].unusable_before == 0 &&
           CcwDelta(beams_[a].angle_rad, beams_[b].angle_rad) <= options_.max_beam_gap_rad;
  };
  const double jump = options_.depth_edge_m;
  for (size_t k = 0; k < m; ++k) {
    const size_t b = Next(k);
    if (!adjacent(k, b)) continue;
    const double ra = beams_[k].range_m;
    const double rb = beams_[b].range_m;
    // A lone beam between the two sides of one edge (a mixed pixel) is one edge, not two: the
    // edge is counted at the pair (lone beam, its successor) only when the lone beam does not
    // lie between its neighbours.
    const bool a_lone = splits_[Previous(k)] && splits_[k];
    if (a_lone && m > 2) {
      const size_t before = Previous(k);
      if (adjacent(before, k)) {
        const double r0 = beams_[before].range_m;
        if (std::abs(r0 - rb) > jump && std::min(r0, rb) < ra && ra < std::max(r0, rb)) continue;
      }
    }
    const bool b_lone = splits_[k] && splits_[b];
    if (b_lone && m > 2) {
      const size_t after = Next(b);
      if (adjacent(b, after)) {
        const double rc = beams_[after].range_m;
        if (std::abs(ra - rc) > jump && std::min(ra, rc) < rb && rb < std::max(ra, rc)) {
          ++stats_.depth_edges;
          continue;
        }
      }
    }
    if (std::abs(ra - rb) > jump) ++stats_.depth_edges;
  }
}

bool Segmenter::ExplainedByCircle(size_t count, double lines_rms_m, size_t runs) const {
  const CircleFit circle = FitCircleKasa(sensor_x_.data(), sensor_y_.data(), count);
  if (!circle.ok || circle.radius_m > options_.max_width_m) return false;
  // The centre lies behind the points, seen from the sensor.
  const Eigen::Vector2d centroid = Centroid(sensor_x_.data(), sensor_y_.data(), count);
  const double cx = circle.centre_x_m;
  const double cy = circle.centre_y_m;
  if (!(cx * cx + cy * cy > centroid.squaredNorm())) return false;
  return circle.rms_residual_m <=
         (runs >= 2 ? kRoundRmsRatioRuns : kRoundRmsRatioOneRun) * lines_rms_m;
}

double Segmenter::SplitDistance(double range_m) const {
  return options_.line_split_distance_m + options_.line_split_range_fraction * range_m;
}

double Segmenter::MeanRange(size_t count) const {
  double sum = 0.0;
  for (size_t i = 0; i < count; ++i) sum += std::hypot(sensor_x_[i], sensor_y_[i]);
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

void Segmenter::FillRunPoints(size_t ring_start, size_t count, size_t offset) {
  if (sensor_x_.size() < offset + count) {
    sensor_x_.resize(offset + count);
    sensor_y_.resize(offset + count);
  }
  size_t k = ring_start;
  for (size_t i = offset; i < offset + count; ++i, k = Next(k)) {
    const Eigen::Vector2d point = BeamPoint(k);
    sensor_x_[i] = point.x();
    sensor_y_[i] = point.y();
  }
}

Eigen::Vector2d Segmenter::BeamPoint(size_t k) const {
  double sin_a = 0.0;
  double cos_a = 0.0;
  SinCosSeries(beams_[k].angle_rad, &sin_a, &cos_a);
  return beams_[k].range_m * Eigen::Vector2d(cos_a, sin_a);
}

size_t Segmenter::LastBeam(const RingRun& run) const {
  size_t k = run.ring_start;
  for (size_t i = 1; i < run.count; ++i) k = Next(k);
  return k;
}

size_t Segmenter::FillFitPoints(const RingRun& run, size_t offset) {
  size_t k = run.ring_start;
  for (size_t i = 0; i < run.skip_first; ++i) k = Next(k);
  const size_t count = run.count - run.skip_first - run.skip_last;
  FillRunPoints(k, count, offset);
  return count;
}

LineFeature Segmenter::MakeLine(size_t fit_count, const RingRun& first, const RingRun& last) {
  const double* x = sensor_x_.data();
  const double* y = sensor_y_.data();
  const LineFit fit = FitLine(x, y, fit_count, options_.sigma_r_m, options_.bearing_sigma_rad);
  LineFeature line;
  line.rho_m = fit.rho_m;
  line.alpha_rad = fit.alpha_rad;
  line.covariance = fit.covariance;
  line.num_points = static_cast<int>(fit_count);
  line.rms_residual_m = fit.rms_residual_m;
  const double ca = std::cos(fit.alpha_rad);
  const double sa = std::sin(fit.alpha_rad);
  // The extent: the runs' end beams (a corner left out of the fit still bounds what was seen).
  const size_t last_beam = LastBeam(last);
  const auto project = [&](size_t k) {
    const Eigen::Vector2d p = BeamPoint(k);
    const double e = DistanceFromLine(fit.rho_m, ca, sa, p.x(), p.y());
    return Eigen::Vector2d(p.x() - e * ca, p.y() - e * sa);
  };
  line.first_point_m = project(first.ring_start);
  line.last_point_m = project(last_beam);
  line.first_beam_index = beams_[first.ring_start].index;
  line.last_beam_index = beams_[last_beam].index;
  return line;
}

bool Segmenter::TryMergeLines(size_t first, size_t second, LineFeature* merged) {
  const LineFeature& a = lines_[first];
  const LineFeature& b = lines_[second];
  if (line_runs_[first].merged || line_runs_[second].merged ||
      !(std::abs(WrapAngle(a.alpha_rad - b.alpha_rad)) < kMergeAngleRad) ||
      !(std::abs(a.rho_m - b.rho_m) < 2.0 * SplitDistance(std::max(a.rho_m, b.rho_m)))) {
    return false;
  }
  const RingRun& ra = line_runs_[first];
  const RingRun& rb = line_runs_[second];
  // Two runs of one cluster that share their corner point and become one line fit it once.
  RingRun fit_a = ra;
  RingRun fit_b = rb;
  if (options_.line_fit_without_shared_corners && LastBeam(ra) == rb.ring_start) {
    fit_a.skip_last = 0;
    fit_b.skip_first = 1;
  }
  const size_t na = FillFitPoints(fit_a, 0);
  const size_t n = na + FillFitPoints(fit_b, na);
  const LineFit fit = FitLine(sensor_x_.data(), sensor_y_.data(), n, options_.sigma_r_m,
                              options_.bearing_sigma_rad);
  const double ca = std::cos(fit.alpha_rad);
  const double sa = std::sin(fit.alpha_rad);
  const double tolerance = SplitDistance(MeanRange(n));
  for (size_t i = 0; i < n; ++i) {
    if (!(std::abs(DistanceFromLine(fit.rho_m, ca, sa, sensor_x_[i], sensor_y_[i])) <=
          tolerance)) {
      return false;
    }
  }
  *merged = MakeLine(n, ra, rb);  // the fitted points of both runs are in the buffer
  return true;
}

void Segmenter::MergeCollinearLines() {
  // Neighbours in scan order only, so that the extent stays the span the scan met; a line
  // merges once (its beams are then two runs of the ring).
  size_t kept = 0;
  LineFeature merged;
  for (size_t j = 1; j < lines_.size(); ++j) {
    if (TryMergeLines(kept, j, &merged)) {
      lines_[kept] = merged;
      line_runs_[kept].merged = true;
    } else {
      ++kept;
      lines_[kept] = lines_[j];
      line_runs_[kept] = line_runs_[j];
    }
  }
  if (lines_.empty()) return;
  lines_.resize(kept + 1);
  line_runs_.resize(kept + 1);
  // Around a 360-degree scan the last line and the first may be one wall across the seam.
  if (kept > 0 && TryMergeLines(kept, 0, &merged)) {
    lines_[0] = merged;
    line_runs_[0].merged = true;
    lines_.pop_back();
    line_runs_.pop_back();
  }
}

void Segmenter::ExtractLines() {
  lines_.clear();
  line_runs_.clear();
  structure_.assign(clusters_.size(), 0);
  stats_.clusters_structure = 0;
  stats_.clusters_round = 0;
  stats_.beams_on_lines = 0;
  stats_.lines = 0;
  if (!options_.extract_lines) return;
  const size_t min_points = static_cast<size_t>(options_.min_line_points);
  const double min_length2 = options_.min_line_length_m * options_.min_line_length_m;
  for (size_t ci = 0; ci < clusters_.size(); ++ci) {
    const Cluster& c = clusters_[ci];
    if (c.count < min_points) continue;
    FillRunPoints(c.ring_start, c.count, 0);
    SplitAndMerge(sensor_x_.data(), sensor_y_.data(), c.count, SplitDistance(MeanRange(c.count)),
                  &runs_, &run_stack_);
    const auto qualifies = [&](const PointRun& run) {
      if (run.size() < min_points) return false;
      const double dx = sensor_x_[run.end - 1] - sensor_x_[run.begin];
      const double dy = sensor_y_[run.end - 1] - sensor_y_[run.begin];
      return dx * dx + dy * dy >= min_length2;
    };
    size_t qualifying = 0;
    for (const PointRun& run : runs_) qualifying += qualifies(run);
    if (qualifying == 0) continue;
    const size_t last = c.count - 1;
    const double width = std::hypot(sensor_x_[last] - sensor_x_[0], sensor_y_[last] - sensor_y_[0]);
    if (width <= options_.max_width_m) {
      // A compact cluster may be a large round object that the runs only approximate.
      double sum_e2 = 0.0;
      double points = 0.0;
      for (const PointRun& run : runs_) {
        if (run.size() < 3) continue;
        const LineFit fit = FitLine(sensor_x_.data() + run.begin, sensor_y_.data() + run.begin,
                                    run.size(), options_.sigma_r_m, options_.bearing_sigma_rad);
        sum_e2 += fit.rms_residual_m * fit.rms_residual_m * static_cast<double>(run.size());
        points += static_cast<double>(run.size());
      }
      if (points > 0.0 && ExplainedByCircle(c.count, std::sqrt(sum_e2 / points), runs_.size())) {
        ++stats_.clusters_round;
        continue;
      }
    }
    structure_[ci] = 1;
    ++stats_.clusters_structure;
    FitRangesOfRuns(runs_, options_.line_fit_without_shared_corners, &run_fits_);
    size_t covered_end = 0;  // runs share their corner points: count each beam once
    for (size_t r = 0; r < runs_.size(); ++r) {
      const PointRun& run = runs_[r];
      if (!qualifies(run)) continue;
      size_t k = c.ring_start;
      for (size_t i = 0; i < run.begin; ++i) k = Next(k);
      line_runs_.push_back(RingRun{k, run.size(), run_fits_[r].fit_begin - run.begin,
                                   run.end - run_fits_[r].fit_end, false});
      stats_.beams_on_lines +=
          static_cast<int64_t>(run.end - std::max(run.begin, std::min(covered_end, run.end)));
      covered_end = std::max(covered_end, run.end);
    }
  }
  for (const RingRun& run : line_runs_) {
    lines_.push_back(MakeLine(FillFitPoints(run, 0), run, run));
  }
  MergeCollinearLines();
  stats_.lines = static_cast<int64_t>(lines_.size());
}

void Segmenter::FillSensorFromCluster(size_t count, double reference_bearing_rad) {
  double sin_r = 0.0;
  double cos_r = 0.0;
  SinCosSeries(WrapAngle(reference_bearing_rad), &sin_r, &cos_r);
  if (sensor_x_.size() < count) {
    sensor_x_.resize(count);
    sensor_y_.resize(count);
  }
  for (size_t i = 0; i < count; ++i) {
    sensor_x_[i] = x_[i] * cos_r - y_[i] * sin_r;
    sensor_y_[i] = x_[i] * sin_r + y_[i] * cos_r;
  }
}

bool Segmenter::IsStructurePiece(const ClusterView& cluster, double width_m, bool leg_like) {
  const size_t count = cluster.count;
  double sum_range = 0.0;
  for (size_t i = 0; i < count; ++i) sum_range += cluster.range_m[i];
  const double split = SplitDistance(sum_range / static_cast<double>(count));
  // Straight, and too wide for a leg (with enough points for straightness to mean something:
  // three points of a far post are always "straight") or seen only between two nearer objects.
  const bool enough_points = count >= static_cast<size_t>(options_.min_line_points);
  if (MaxDistanceFromChord(cluster.x_m, cluster.y_m, count) <= split) {
    return (enough_points && width_m >= options_.straight_piece_width_m) ||
           (cluster.first_edge_occluded && cluster.last_edge_occluded);
  }
  // Wider than a leg, not leg-like and not round: a few straight pieces (a corner).
  if (!enough_points || width_m < options_.straight_piece_width_m || leg_like) return false;
  SplitAndMerge(cluster.x_m, cluster.y_m, count, split, &runs_, &run_stack_);
  double sum_e2 = 0.0;
  double points = 0.0;
  for (const PointRun& run : runs_) {
    if (run.size() < 3) continue;
    const LineFit fit = FitLine(cluster.x_m + run.begin, cluster.y_m + run.begin, run.size(),
                                options_.sigma_r_m, options_.bearing_sigma_rad);
    sum_e2 += fit.rms_residual_m * fit.rms_residual_m * static_cast<double>(run.size());
    points += static_cast<double>(run.size());
  }
  if (!(points > 0.0)) return false;  // runs of two points: curved all along, no corner
  // ExplainedByCircle reads sensor_x_/sensor_y_: the rotated frame serves as well.
  if (sensor_x_.size() < count) {
    sensor_x_.resize(count);
    sensor_y_.resize(count);
  }
  std::copy(cluster.x_m, cluster.x_m + count, sensor_x_.begin());
  std::copy(cluster.y_m, cluster.y_m + count, sensor_y_.begin());
  return !ExplainedByCircle(count, std::sqrt(sum_e2 / points), runs_.size());
}

void Segmenter::ClassifyLoneBeam(const Cluster& c) {
  const size_t k = c.ring_start;
  const size_t m = beams_.size();
  bool mixed = false;
  if (m >= 3) {
    const size_t before = Previous(k);
    const size_t after = Next(k);
    const double limit = options_.max_beam_gap_rad;
    const bool neighbours = beams_[k].unusable_before == 0 && beams_[after].unusable_before == 0 &&
                            CcwDelta(beams_[before].angle_rad, beams_[k].angle_rad) <= limit &&
                            CcwDelta(beams_[k].angle_rad, beams_[after].angle_rad) <= limit;
    const double r0 = beams_[before].range_m;
    const double r1 = beams_[after].range_m;
    const double r = beams_[k].range_m;
    mixed = neighbours && std::abs(r0 - r1) > options_.depth_edge_m && std::min(r0, r1) < r &&
            r < std::max(r0, r1);
  }
  if (mixed) {
    ++stats_.beams_mixed_pixel;
  } else {
    ++stats_.beams_isolated;
  }
}

bool Segmenter::LiesOnALine(size_t count, double tolerance_m) const {
  const double tolerance = tolerance_m;
  for (const LineFeature& line : lines_) {
    const double ca = std::cos(line.alpha_rad);
    const double sa = std::sin(line.alpha_rad);
    bool all = true;
    for (size_t i = 0; i < count && all; ++i) {
      all = std::abs(DistanceFromLine(line.rho_m, ca, sa, sensor_x_[i], sensor_y_[i])) <=
            tolerance;
    }
    if (all) return true;
  }
  return false;
}

void Segmenter::MakeFeature(const Cluster& c) {
  const size_t ring_start = c.ring_start;
  const size_t count = c.count;
  const size_t m = beams_.size();
  bool provisional = false;
  if (count < static_cast<size_t>(options_.min_points)) {
    ++stats_.clusters_too_few_points;
    if (count == 1) {
      ClassifyLoneBeam(c);
      return;
    }
    // Two points: a provisional leg where a leg shows fewer than min_points beams.
    if (count != 2 || !options_.detect_people) return;
    const Beam& a = beams_[ring_start];
    const Beam& b = beams_[Next(ring_start)];
    const double beam_m = 0.5 * (a.range_m + b.range_m) * CcwDelta(a.angle_rad, b.angle_rad);
    if (!(options_.leg_nominal_diameter_m < options_.min_points * beam_m)) return;
    provisional = true;
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
  // A centre far behind every point (a circle fitted to a nearly straight cluster) is no
  // better than the radius-corrected one.
  double farthest_point = 0.0;
  for (size_t i = 0; i < count; ++i) farthest_point = std::max(farthest_point, range_[i]);
  if (options_.centre_rule == CentreRule::kCircleFit &&
      centre.range_m > farthest_point + options_.max_object_radius_m) {
    centre = corrected;
    ++stats_.circle_fit_fallbacks;
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
  feature.leg_likeness = ScoreLegLikeness(cluster, ring_start, last_ring_index, spacing,
                                          reference_bearing, &feature.bounded_edges);
  feature.leg_cluster = static_cast<int32_t>(leg_clusters_.size()) - 1;
  const bool leg_like = feature.leg_likeness >= options_.leg_threshold;
  if (provisional && !leg_like) {
    leg_clusters_.back().fate = LegClusterFate::kNotALeg;
    return;
  }
  // Pieces of structure are looked for in scans that show structure (a line feature): in a
  // world of round objects, a far post of five points is as flat as the noise allows.
  if (!lines_.empty() && count >= 3 && IsStructurePiece(cluster, width, leg_like)) {
    ++stats_.clusters_structure_pieces;
    leg_clusters_.back().fate = LegClusterFate::kStructurePiece;
    return;
  }
  if (!lines_.empty()) {
    // A piece of a line of this scan? Test its points in the sensor frame: within the split
    // distance, unless it looks like a leg with more than three points (a person in a doorway
    // stands on the wall's line), which must then lie within kOnSurfaceM of the line, closer
    // than a leg's round outline can.
    FillSensorFromCluster(count, reference_bearing);
    const bool loose = count <= 3 || !leg_like;
    if (LiesOnALine(count, loose ? SplitDistance(MeanRange(count)) : kOnSurfaceM)) {
      ++stats_.clusters_on_lines;
      leg_clusters_.back().fate = LegClusterFate::kOnALine;
      return;
    }
  }
  (provisional ? provisional_ : features_).push_back(feature);
}

double Segmenter::ScoreLegLikeness(const ClusterView& cluster, size_t ring_start,
                                   size_t last_ring_index, double spacing_rad,
                                   double reference_bearing_rad, int* bounded_edges) {
  const size_t m = beams_.size();
  const size_t count = cluster.count;
  // The beams just outside the cluster: none when a beam without a usable return lies between
  // (counted in unusable_before) or the cluster is the whole ring.
  ClusterSurroundings around;
  around.scan_spacing_rad = spacing_rad;
  if (count < m) {
    const size_t before = Previous(ring_start);
    const size_t after = Next(last_ring_index);
    const double gap = options_.max_beam_gap_rad;
    if (beams_[ring_start].unusable_before == 0 &&
        CcwDelta(beams_[before].angle_rad, beams_[ring_start].angle_rad) <= gap) {
      around.range_before_m = beams_[before].range_m;
    }
    if (beams_[after].unusable_before == 0 &&
        CcwDelta(beams_[last_ring_index].angle_rad, beams_[after].angle_rad) <= gap) {
      around.range_after_m = beams_[after].range_m;
    }
  }
  // An edge is bounded where the beam just outside had a usable return.
  *bounded_edges = std::isfinite(around.range_before_m) + std::isfinite(around.range_after_m);
  LegClusterRecord record;
  record.features = ComputeLegFeatures(cluster, around);
  const Eigen::Vector2d centroid = Centroid(cluster.x_m, cluster.y_m, count);
  const double c = std::cos(reference_bearing_rad);
  const double s = std::sin(reference_bearing_rad);
  record.centroid_x_m = centroid.x() * c - centroid.y() * s;
  record.centroid_y_m = centroid.x() * s + centroid.y() * c;
  switch (options_.leg_classifier) {
    case LegClassifier::kTrained:
      record.leg_likeness = LegProbability(*leg_model_, record.features);
      break;
    case LegClassifier::kShape:
      record.leg_likeness = LegLikeness(DescribeClusterShape(cluster, spacing_rad), options_.leg,
                                        options_.sigma_r_m);
      break;
  }
  leg_clusters_.push_back(record);
  return record.leg_likeness;
}

std::vector<Feature> SegmentScan(const ScanView& scan, const SegmenterOptions& options) {
  Segmenter segmenter(options);
  return segmenter.Segment(scan);
}

}  // namespace slammtt
