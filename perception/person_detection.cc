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

}  // namespace

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
                            std::vector<PersonFeature>* people, std::vector<uint8_t>* used) {
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
    if ((*used)[i] || c.provisional || !Finite(c) || c.surface_piece ||
        c.leg_likeness < options.single_leg_threshold) {
      continue;
    }
    (*used)[i] = 1;
    const Eigen::Matrix2d cartesian =
        PolarToCartesianCovariance(c.range_m, c.bearing_rad, c.covariance) +
        single_var * Eigen::Matrix2d::Identity();
    PersonFeature person = MakePerson(positions_[i], cartesian);
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
