#include "perception/person_detection.h"

#include <algorithm>
#include <cmath>

#include "common/angle.h"

namespace slammtt {
namespace {

// d(x, y) / d(range, bearing) at (range, bearing).
Eigen::Matrix2d PolarJacobian(double range_m, double bearing_rad) {
  const double c = std::cos(bearing_rad);
  const double s = std::sin(bearing_rad);
  Eigen::Matrix2d j;
  j << c, -range_m * s, s, range_m * c;
  return j;
}

bool Finite(const LegCandidate& c) {
  return std::isfinite(c.range_m) && c.range_m > 0.0 && std::isfinite(c.bearing_rad) &&
         c.covariance.allFinite() && std::isfinite(c.leg_likeness);
}

PersonFeature MakePerson(const Eigen::Vector2d& centre, const Eigen::Matrix2d& cartesian) {
  PersonFeature person;
  person.range_m = centre.norm();
  person.bearing_rad = WrapAngle(std::atan2(centre.y(), centre.x()));
  person.covariance = CartesianToPolarCovariance(centre.x(), centre.y(), cartesian);
  return person;
}

// A hidden leg's centre is behind whatever hides it by at least its radius and the noise.
constexpr double kHiddenLegMarginM = 0.09;
// The polar grid of places of the other leg around the visible one.
constexpr int kSeparationSteps = 13;
constexpr int kDirectionSteps = 36;

// The mean place of the other leg among the places the scan cannot see (the visible leg's
// midpoint with it is the body's centre); the leg itself when the scan sees every place.
Eigen::Vector2d HiddenLegMean(const Eigen::Vector2d& leg, const SightLines& sight,
                              const PersonDetectionOptions& options) {
  const double range = leg.norm();
  if (!(range > 0.0)) return leg;
  const Eigen::Vector2d along = leg / range;
  const Eigen::Vector2d across(-along.y(), along.x());
  const double lo = std::max(options.min_leg_separation_m, 1e-3);
  const double step = (options.max_leg_separation_m - lo) / (kSeparationSteps - 1);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int hidden = 0;
  for (int k = 0; k < kDirectionSteps; ++k) {
    const double phi = 2.0 * M_PI * k / kDirectionSteps;
    const Eigen::Vector2d direction = std::cos(phi) * along + std::sin(phi) * across;
    for (int i = 0; i < kSeparationSteps; ++i) {
      const Eigen::Vector2d offset = (lo + step * i) * direction;
      if (!sight.Hides(leg + offset, kHiddenLegMarginM)) continue;
      sum += offset;
      ++hidden;
    }
  }
  return hidden > 0 ? Eigen::Vector2d(leg + sum / hidden) : leg;
}

}  // namespace

bool SightLines::Hides(const Eigen::Vector2d& point, double margin_m) const {
  if (count == 0 || angle_rad == nullptr || range_m == nullptr) return true;
  const double bearing = std::atan2(point.y(), point.x());
  // Neighbours in angle, around the circle.
  const double* end = angle_rad + count;
  const double* upper = std::lower_bound(angle_rad, end, bearing);
  const size_t after = upper == end ? 0 : static_cast<size_t>(upper - angle_rad);
  const size_t before = after == 0 ? count - 1 : after - 1;
  double gap = angle_rad[after] - angle_rad[before];
  if (gap <= 0.0) gap += 2.0 * M_PI;
  if (count == 1 || gap > max_gap_rad) return true;  // no beam there: unknown
  double to_before = bearing - angle_rad[before];
  if (to_before < 0.0) to_before += 2.0 * M_PI;
  const size_t nearest = to_before <= 0.5 * gap ? before : after;
  return range_m[nearest] < point.norm() - margin_m;
}

Eigen::Matrix2d PolarToCartesianCovariance(double range_m, double bearing_rad,
                                           const Eigen::Matrix2d& polar) {
  const Eigen::Matrix2d j = PolarJacobian(range_m, bearing_rad);
  return j * polar * j.transpose();
}

Eigen::Matrix2d CartesianToPolarCovariance(double x_m, double y_m,
                                           const Eigen::Matrix2d& cartesian) {
  const double r2 = x_m * x_m + y_m * y_m;
  const double r = std::sqrt(r2);
  Eigen::Matrix2d j;  // d(range, bearing) / d(x, y)
  if (r > 1e-9) {
    j << x_m / r, y_m / r, -y_m / r2, x_m / r2;
  } else {
    j = Eigen::Matrix2d::Identity();
  }
  Eigen::Matrix2d polar = j * cartesian * j.transpose();
  polar(0, 1) = polar(1, 0) = 0.5 * (polar(0, 1) + polar(1, 0));
  return polar;
}

void PersonDetector::Detect(const std::vector<LegCandidate>& candidates,
                            const PersonDetectionOptions& options,
                            std::vector<PersonFeature>* people, std::vector<uint8_t>* used,
                            const SightLines* sight) {
  people->clear();
  used->assign(candidates.size(), 0);
  positions_.resize(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) {
    const LegCandidate& c = candidates[i];
    positions_[i] = c.range_m * Eigen::Vector2d(std::cos(c.bearing_rad), std::sin(c.bearing_rad));
  }
  pairs_.clear();
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!Finite(candidates[i])) continue;
    for (size_t j = i + 1; j < candidates.size(); ++j) {
      if (!Finite(candidates[j])) continue;
      if (candidates[i].provisional && candidates[j].provisional) continue;
      if (candidates[i].surface_piece && candidates[j].surface_piece) continue;
      if (options.separate_dropout_pieces && candidates[i].dropout_run >= 0 &&
          candidates[i].dropout_run == candidates[j].dropout_run) {
        continue;
      }
      const double separation = (positions_[i] - positions_[j]).norm();
      if (separation < options.min_leg_separation_m ||
          separation > options.max_leg_separation_m) {
        continue;
      }
      pairs_.push_back(Pair{separation, static_cast<uint32_t>(i), static_cast<uint32_t>(j)});
    }
  }
  std::sort(pairs_.begin(), pairs_.end(), [](const Pair& a, const Pair& b) {
    if (a.separation_m != b.separation_m) return a.separation_m < b.separation_m;
    if (a.first != b.first) return a.first < b.first;
    return a.second < b.second;
  });
  const double pair_var = options.pair_centre_sigma_m * options.pair_centre_sigma_m;
  for (const Pair& pair : pairs_) {
    if ((*used)[pair.first] || (*used)[pair.second]) continue;
    (*used)[pair.first] = 1;
    (*used)[pair.second] = 1;
    const LegCandidate& a = candidates[pair.first];
    const LegCandidate& b = candidates[pair.second];
    const Eigen::Matrix2d cartesian =
        0.25 * (PolarToCartesianCovariance(a.range_m, a.bearing_rad, a.covariance) +
                PolarToCartesianCovariance(b.range_m, b.bearing_rad, b.covariance)) +
        pair_var * Eigen::Matrix2d::Identity();
    PersonFeature person =
        MakePerson(0.5 * (positions_[pair.first] + positions_[pair.second]), cartesian);
    person.num_legs = 2;
    person.leg_index[0] = a.feature_index;
    person.leg_index[1] = b.feature_index;
    person.confidence = std::sqrt(std::clamp(a.leg_likeness, 0.0, 1.0) *
                                  std::clamp(b.leg_likeness, 0.0, 1.0));
    people->push_back(person);
  }
  const double single_var = options.single_leg_offset_sigma_m * options.single_leg_offset_sigma_m;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const LegCandidate& c = candidates[i];
    const double threshold =
        options.single_leg_threshold + options.single_leg_open_edge_step * c.open_edges;
    if ((*used)[i] || c.provisional || !Finite(c) || c.surface_piece ||
        c.leg_likeness < threshold ||
        c.surface_clearance_m < options.single_leg_surface_clearance_m ||
        (options.separate_dropout_pieces && c.dropout_run >= 0)) {
      continue;
    }
    if (c.open_edges > 0 && c.num_points > 0 &&
        c.num_points <= options.single_leg_open_edge_max_points) {
      (*used)[i] = kStubLeg;
      continue;
    }
    (*used)[i] = 1;
    const Eigen::Matrix2d cartesian =
        PolarToCartesianCovariance(c.range_m, c.bearing_rad, c.covariance) +
        single_var * Eigen::Matrix2d::Identity();
    const Eigen::Vector2d centre =
        sight != nullptr && options.hidden_leg_centre
            ? Eigen::Vector2d(0.5 * (positions_[i] + HiddenLegMean(positions_[i], *sight, options)))
            : positions_[i];
    PersonFeature person = MakePerson(centre, cartesian);
    person.num_legs = 1;
    person.leg_index[0] = c.feature_index;
    person.confidence = 0.5 * std::clamp(c.leg_likeness, 0.0, 1.0);
    people->push_back(person);
  }
  // std::sort with a total order (std::stable_sort would allocate): each leg is in one person.
  std::sort(people->begin(), people->end(), [](const PersonFeature& a, const PersonFeature& b) {
    if (a.bearing_rad != b.bearing_rad) return a.bearing_rad < b.bearing_rad;
    return a.leg_index[0] < b.leg_index[0];
  });
}

}  // namespace slammtt
