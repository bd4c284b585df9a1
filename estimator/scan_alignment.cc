#include "estimator/scan_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angle.h"
#include "common/utime.h"

namespace slammtt {
namespace {

Eigen::Matrix2d Rotation(double angle_rad) {
  return Eigen::Rotation2Dd(angle_rad).toRotationMatrix();
}

// d Rotation / d angle.
Eigen::Matrix2d RotationDerivative(double angle_rad) {
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  Eigen::Matrix2d d;
  d << -s, -c, c, -s;
  return d;
}

Eigen::Vector2d SensorToRobot(const SensorMount& mount, const Eigen::Vector2d& sensor_point) {
  return Eigen::Vector2d(mount.forward_m, mount.left_m) + Rotation(mount.yaw_rad) * sensor_point;
}

double CauchyWeight(double residual, double scale) {
  const double u = residual / scale;
  return 1.0 / (1.0 + u * u);
}

// The normal equations of one iteration: H delta = -b.
struct NormalEquations {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  int point_pairs = 0;
  int line_pairs = 0;

  void Add(const Eigen::Matrix<double, 1, 3>& jacobian, double residual, double sigma,
           double robust_scale) {
    const double w = CauchyWeight(residual, robust_scale * sigma) / (sigma * sigma);
    h.noalias() += w * jacobian.transpose() * jacobian;
    b.noalias() += w * jacobian.transpose() * residual;
  }
};

// The reference point nearest to `q` within match_m, or -1.
int NearestPoint(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q,
                 double match_m) {
  int best = -1;
  double best_d2 = match_m * match_m;
  for (size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - q).squaredNorm();
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void AddPointPairs(const AlignmentScan& reference, const AlignmentScan& scan,
                   const Eigen::Vector3d& x, const ScanAlignmentOptions& options,
                   NormalEquations* eq) {
  const Eigen::Matrix2d r = Rotation(x.z());
  const Eigen::Matrix2d dr = RotationDerivative(x.z());
  for (const Eigen::Vector2d& p : scan.points_m) {
    const Eigen::Vector2d q = r * p + x.head<2>();
    const int k = NearestPoint(reference.points_m, q, options.match_m);
    if (k < 0) continue;
    const Eigen::Vector2d residual = q - reference.points_m[static_cast<size_t>(k)];
    const Eigen::Vector2d turn = dr * p;
    // One weight for both coordinates: the Cauchy weight of the distance.
    const double w = CauchyWeight(residual.norm(), options.robust_scale * options.point_sigma_m) /
                     (options.point_sigma_m * options.point_sigma_m);
    Eigen::Matrix<double, 2, 3> j;
    j << 1.0, 0.0, turn.x(), 0.0, 1.0, turn.y();
    eq->h.noalias() += w * j.transpose() * j;
    eq->b.noalias() += w * j.transpose() * residual;
    ++eq->point_pairs;
  }
}

// The angle within which two lines are parallel: match_angle, or 3 sigmas of the difference of
// their directions when wider; at most a right angle.
double ParallelWithin_rad(double direction_var_a, double direction_var_b,
                          const ScanAlignmentOptions& options) {
  return std::min(M_PI / 2,
                  std::max(options.match_angle_rad, 3.0 * std::sqrt(direction_var_a +
                                                                    direction_var_b)));
}

// The reference segment that the segment (e1, e2) of the previous frame, of direction variance
// `direction_var`, continues: parallel (ParallelWithin_rad), both ends within match_m of its
// line, extents overlapping or within match_m; the one with the smallest summed distance. -1
// when none.
int MatchingSegment(const std::vector<AlignmentSegment>& segments, const Eigen::Vector2d& e1,
                    const Eigen::Vector2d& e2, double direction_var,
                    const ScanAlignmentOptions& options) {
  const Eigen::Vector2d d = (e2 - e1).normalized();
  int best = -1;
  double best_sum = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < segments.size(); ++i) {
    const Eigen::Vector2d along = segments[i].to_m - segments[i].from_m;
    const double length = along.norm();
    const Eigen::Vector2d u = along / length;
    const double max_sine =
        std::sin(ParallelWithin_rad(direction_var, segments[i].direction_var_rad2, options));
    if (std::abs(d.x() * u.y() - d.y() * u.x()) > max_sine) continue;
    const Eigen::Vector2d n(-u.y(), u.x());
    const double d1 = std::abs(n.dot(e1 - segments[i].from_m));
    const double d2 = std::abs(n.dot(e2 - segments[i].from_m));
    if (d1 > options.match_m || d2 > options.match_m) continue;
    const double s1 = u.dot(e1 - segments[i].from_m);
    const double s2 = u.dot(e2 - segments[i].from_m);
    const double gap = std::max({0.0, std::min(s1, s2) - length, -std::max(s1, s2)});
    if (gap > options.match_m || d1 + d2 >= best_sum) continue;
    best_sum = d1 + d2;
    best = static_cast<int>(i);
  }
  return best;
}

void AddLinePairs(const AlignmentScan& reference, const AlignmentScan& scan,
                  const Eigen::Vector3d& x, const ScanAlignmentOptions& options,
                  NormalEquations* eq) {
  const Eigen::Matrix2d r = Rotation(x.z());
  const Eigen::Matrix2d dr = RotationDerivative(x.z());
  for (const AlignmentSegment& s : scan.segments) {
    const Eigen::Vector2d e1 = r * s.from_m + x.head<2>();
    const Eigen::Vector2d e2 = r * s.to_m + x.head<2>();
    const int k = MatchingSegment(reference.segments, e1, e2, s.direction_var_rad2, options);
    if (k < 0) continue;
    const AlignmentSegment& ref = reference.segments[static_cast<size_t>(k)];
    const Eigen::Vector2d u = (ref.to_m - ref.from_m).normalized();
    const Eigen::Vector2d n(-u.y(), u.x());
    const Eigen::Vector2d ref_middle = 0.5 * (ref.from_m + ref.to_m);
    const double half_length = 0.5 * (s.to_m - s.from_m).norm();
    for (const auto& [end, local] : {std::make_pair(e1, s.from_m), std::make_pair(e2, s.to_m)}) {
      Eigen::Matrix<double, 1, 3> j;
      j << n.x(), n.y(), n.dot(dr * local);
      const double from_middle = u.dot(end - ref_middle);
      const double sigma = std::sqrt(options.line_sigma_m * options.line_sigma_m +
                                     ref.direction_var_rad2 * from_middle * from_middle +
                                     s.direction_var_rad2 * half_length * half_length);
      eq->Add(j, n.dot(end - ref.from_m), sigma, options.robust_scale);
    }
    ++eq->line_pairs;
  }
}

bool Finite(const Eigen::Vector2d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// An angle modulo pi (a line has no direction), in (-pi/2, pi/2].
double WrapHalfTurn(double angle_rad) {
  double a = WrapAngle(angle_rad);
  if (a > M_PI / 2) a -= M_PI;
  if (a <= -M_PI / 2) a += M_PI;
  return a;
}

struct LineShape {
  double direction_rad = 0.0;
  double distance_m = 0.0;  // of the infinite line from the robot
  double length_m = 0.0;
};

LineShape ShapeOf(const AlignmentSegment& s) {
  const Eigen::Vector2d along = s.to_m - s.from_m;
  const double length = along.norm();
  const Eigen::Vector2d n(-along.y() / length, along.x() / length);
  return {std::atan2(along.y(), along.x()), std::abs(n.dot(s.from_m)), length};
}

}  // namespace

void VisitScanAlignmentOptions(OptionVisitor* v, ScanAlignmentOptions* o) {
  using R = OptionRange;
  v->Bool("enabled", &o->enabled,
          "with no ODOMETRY received, the robot moves by aligning consecutive scans");
  v->Int("max_iterations", &o->max_iterations, R::Between(1, 100),
         "Gauss-Newton iterations of one alignment (associations renewed at each)");
  v->Double("match_m", &o->match_m, R::Above(0),
            "a feature pairs with one of the previous scan within this distance...");
  v->Double("match_angle_rad", &o->match_angle_rad, R::AboveUpTo(0, 90),
            "...and two lines only when parallel within this angle", OptionUnit::kDegrees);
  v->Double("point_sigma_m", &o->point_sigma_m, R::Above(0),
            "sigma of a point pair's distance, per coordinate");
  v->Double("line_sigma_m", &o->line_sigma_m, R::Above(0),
            "sigma of a line end's distance to the previous scan's line");
  v->Double("robust_scale", &o->robust_scale, R::Above(0),
            "Cauchy kernel scale, in sigmas: a pair this far off weighs half");
  v->Double("covariance_scale", &o->covariance_scale, R::AtLeast(1),
            "the alignment's covariance is its information's inverse times this");
  v->Double("guess_speed_sigma_mps", &o->guess_speed_sigma_mps, R::Above(0),
            "prior of the constant-velocity guess: change of speed per second");
  v->Double("guess_turn_sigma_radps", &o->guess_turn_sigma_radps, R::Above(0),
            "... and of turn rate per second", OptionUnit::kDegrees);
  v->Double("max_turn_search_rad", &o->max_turn_search_rad, R::AboveUpTo(0, 90),
            "the lines' vote for the turn is searched within this of the guess's",
            OptionUnit::kDegrees);
  v->Double("velocity_walk_mps2", &o->velocity_walk_mps2, R::AtLeast(0),
            "the velocity is filtered, its covariance growing by this squared per second (0: "
            "off, the guess's prior is the fixed guess sigmas)");
  v->Double("velocity_turn_walk_radps", &o->velocity_turn_walk_radps, R::AtLeast(0),
            "... and by this of the turn rate", OptionUnit::kDegrees);
}

namespace {

// Keeps the first `cap` of `items` in the order of `before` (stable: ties in input order),
// counting the others in `dropped`.
template <class T, class Before>
void KeepFirst(int cap, Before before, std::vector<T>* items, int* dropped) {
  const size_t n = static_cast<size_t>(cap);
  if (items->size() <= n) return;
  std::stable_sort(items->begin(), items->end(), before);
  *dropped += static_cast<int>(items->size() - n);
  items->resize(n);
}

// The corner of two segments (see AlignmentScanOf), or nullopt.
std::optional<Eigen::Vector2d> CornerOf(const AlignmentSegment& a, const AlignmentSegment& b) {
  const Eigen::Vector2d u = (a.to_m - a.from_m).normalized();
  const Eigen::Vector2d v = (b.to_m - b.from_m).normalized();
  const double sine = u.x() * v.y() - u.y() * v.x();
  if (std::abs(sine) < std::sin(kMinCornerAngle_rad)) return std::nullopt;
  double gap = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& p : {a.from_m, a.to_m}) {
    for (const Eigen::Vector2d& q : {b.from_m, b.to_m}) gap = std::min(gap, (p - q).norm());
  }
  if (gap > kCornerGap_m) return std::nullopt;
  // a.from + s u = b.from + t v, solved for s.
  const Eigen::Vector2d d = b.from_m - a.from_m;
  const double s = (d.x() * v.y() - d.y() * v.x()) / sine;
  return Eigen::Vector2d(a.from_m + s * u);
}

}  // namespace

AlignmentScan AlignmentScanOf(const std::vector<PointMeasurement>& points,
                              const std::vector<LineReading>& lines, const SensorMount& mount) {
  AlignmentScan scan;
  for (const PointMeasurement& m : points) {
    if (m.person) continue;
    const double range = m.range_bearing.x();
    const double bearing = m.range_bearing.y();
    const Eigen::Vector2d p =
        SensorToRobot(mount, range * Eigen::Vector2d(std::cos(bearing), std::sin(bearing)));
    if (Finite(p)) {
      scan.points_m.push_back(p);
    } else {
      ++scan.skipped;
    }
  }
  for (const LineReading& line : lines) {
    const Eigen::Vector2d n(std::cos(line.alpha_rad), std::sin(line.alpha_rad));
    const Eigen::Vector2d from = line.first_m - (n.dot(line.first_m) - line.rho_m) * n;
    const Eigen::Vector2d to = line.last_m - (n.dot(line.last_m) - line.rho_m) * n;
    AlignmentSegment s{SensorToRobot(mount, from), SensorToRobot(mount, to),
                       line.alpha_var_rad2};
    if (Finite(s.from_m) && Finite(s.to_m) && std::isfinite(s.direction_var_rad2) &&
        s.direction_var_rad2 >= 0.0 &&
        (s.to_m - s.from_m).norm() >= kMinAlignmentSegment_m) {
      scan.segments.push_back(s);
    } else {
      ++scan.skipped;
    }
  }
  KeepFirst(kMaxAlignmentPoints,
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
              return a.squaredNorm() < b.squaredNorm();
            },
            &scan.points_m, &scan.over_cap);
  KeepFirst(kMaxAlignmentSegments,
            [](const AlignmentSegment& a, const AlignmentSegment& b) {
              return (a.to_m - a.from_m).squaredNorm() > (b.to_m - b.from_m).squaredNorm();
            },
            &scan.segments, &scan.over_cap);
  for (size_t i = 0; i < scan.segments.size(); ++i) {
    for (size_t j = i + 1; j < scan.segments.size(); ++j) {
      const std::optional<Eigen::Vector2d> corner = CornerOf(scan.segments[i], scan.segments[j]);
      if (!corner) continue;
      scan.points_m.push_back(*corner);
      ++scan.corners;
    }
  }
  return scan;
}

std::optional<double> TurnFromLines(const AlignmentScan& reference, const AlignmentScan& scan,
                                    double guess_heading_rad, double guess_shift_m,
                                    const ScanAlignmentOptions& options) {
  struct Vote {
    double turn_rad;
    double weight_m;
  };
  std::vector<Vote> votes;
  for (const AlignmentSegment& c : scan.segments) {
    const LineShape current = ShapeOf(c);
    for (const AlignmentSegment& r : reference.segments) {
      const LineShape previous = ShapeOf(r);
      if (std::abs(current.distance_m - previous.distance_m) > options.match_m + guess_shift_m) {
        continue;
      }
      const double turn = WrapHalfTurn(previous.direction_rad - current.direction_rad);
      if (std::abs(WrapHalfTurn(turn - guess_heading_rad)) > options.max_turn_search_rad) {
        continue;
      }
      votes.push_back({turn, std::min(current.length_m, previous.length_m)});
    }
  }
  // Each vote's window of kTurnVoteWidth_rad either side, over the votes sorted by their offset
  // from the guess (all within max_turn_search < pi/2 of it, so no window wraps): two pointers,
  // O(V log V) for V votes.
  for (Vote& v : votes) v.turn_rad = WrapHalfTurn(v.turn_rad - guess_heading_rad);
  std::sort(votes.begin(), votes.end(),
            [](const Vote& a, const Vote& b) { return a.turn_rad < b.turn_rad; });
  double best_support = 0.0;
  double best_turn = 0.0;
  size_t first = 0;
  size_t last = 0;  // the window is [first, last)
  double support = 0.0;
  double weighted_turn = 0.0;
  for (const Vote& candidate : votes) {
    while (last < votes.size() &&
           votes[last].turn_rad <= candidate.turn_rad + kTurnVoteWidth_rad) {
      support += votes[last].weight_m;
      weighted_turn += votes[last].weight_m * votes[last].turn_rad;
      ++last;
    }
    while (votes[first].turn_rad < candidate.turn_rad - kTurnVoteWidth_rad) {
      support -= votes[first].weight_m;
      weighted_turn -= votes[first].weight_m * votes[first].turn_rad;
      ++first;
    }
    if (support > best_support) {
      best_support = support;
      best_turn = weighted_turn / support;
    }
  }
  best_turn = WrapHalfTurn(best_turn + guess_heading_rad);
  if (best_support < kMinTurnVote_m) return std::nullopt;
  return best_turn;
}

ScanAlignment AlignScans(const AlignmentScan& reference, const AlignmentScan& scan,
                         const Eigen::Vector3d& guess, const Eigen::Matrix3d& guess_covariance,
                         const ScanAlignmentOptions& options) {
  const Eigen::Matrix3d prior_information = guess_covariance.inverse();
  ScanAlignment result;
  Eigen::Vector3d x = guess;
  const std::optional<double> turn =
      TurnFromLines(reference, scan, guess.z(), guess.head<2>().norm(), options);
  if (turn) x.z() = *turn;
  NormalEquations eq;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    eq = NormalEquations{};
    eq.h = prior_information;
    Eigen::Vector3d from_guess = x - guess;
    from_guess.z() = WrapAngle(from_guess.z());
    eq.b = prior_information * from_guess;
    AddPointPairs(reference, scan, x, options, &eq);
    AddLinePairs(reference, scan, x, options, &eq);
    const Eigen::Vector3d step = eq.h.ldlt().solve(-eq.b);
    result.iterations = iteration + 1;
    if (!step.allFinite()) break;
    x += step;
    x.z() = WrapAngle(x.z());
    if (step.head<2>().norm() < 1e-6 && std::abs(step.z()) < 1e-7) break;
  }
  result.increment = x;
  result.covariance = options.covariance_scale * eq.h.inverse();
  result.point_pairs = eq.point_pairs;
  result.line_pairs = eq.line_pairs;
  return result;
}

std::optional<ScanAlignment> ScanToScanMotion::MotionTo(const AlignmentScan& scan, double dt_s,
                                                        const ScanAlignmentOptions& options) const {
  if (!reference_) return std::nullopt;
  // A prior of zero width would pin the alignment to the guess: a millisecond at least.
  const double dt = std::max(dt_s, 1e-3);
  const double position_sigma = options.guess_speed_sigma_mps * dt;
  const double heading_sigma = options.guess_turn_sigma_radps * dt;
  const Eigen::Matrix3d prior =
      Eigen::Vector3d(position_sigma * position_sigma, position_sigma * position_sigma,
                      heading_sigma * heading_sigma)
          .asDiagonal();
  if (options.velocity_walk_mps2 > 0.0) {
    // The velocity filtered: its covariance, predicted by the random walk over dt, times dt^2.
    const double walk = options.velocity_walk_mps2 * options.velocity_walk_mps2;
    const double turn_walk = options.velocity_turn_walk_radps * options.velocity_turn_walk_radps;
    const Eigen::Matrix3d unknown =
        Eigen::Vector3d(options.guess_speed_sigma_mps * options.guess_speed_sigma_mps,
                        options.guess_speed_sigma_mps * options.guess_speed_sigma_mps,
                        options.guess_turn_sigma_radps * options.guess_turn_sigma_radps)
            .asDiagonal();
    const Eigen::Matrix3d known =
        velocity_covariance_(0, 0) < 0.0 ? unknown : velocity_covariance_;
    const Eigen::Matrix3d predicted =
        known + Eigen::Vector3d(walk, walk, turn_walk).asDiagonal().toDenseMatrix() * dt;
    return AlignScans(*reference_, scan, velocity_ * dt_s, dt * dt * predicted, options);
  }
  return AlignScans(*reference_, scan, velocity_ * dt_s, prior, options);
}

void ScanToScanMotion::Keep(AlignmentScan scan, const Eigen::Vector3d& pose, int64_t utime,
                            const ScanAlignment* aligned) {
  if (reference_ && utime > utime_) {
    const double dt = SecondsBetween(utime, utime_);
    if (aligned != nullptr) {
      velocity_ = aligned->increment / dt;
      velocity_covariance_ = aligned->covariance / (dt * dt);
    } else {
      const Eigen::Vector2d moved = Rotation(-pose_.z()) * (pose.head<2>() - pose_.head<2>());
      velocity_ << moved / dt, WrapAngle(pose.z() - pose_.z()) / dt;
      velocity_covariance_ = -Eigen::Matrix3d::Identity();
    }
  }
  reference_ = std::move(scan);
  pose_ = pose;
  utime_ = utime;
}

void ScanToScanMotion::Clear() {
  reference_.reset();
  velocity_.setZero();
  velocity_covariance_ = -Eigen::Matrix3d::Identity();
}

}  // namespace slammtt
