#include "estimator/ml_ransac.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "estimator/angle.h"
#include "estimator/range_bearing_model.h"

namespace slammtt {

uint64_t UniformIndex(std::mt19937_64* rng, uint64_t n) {
  const uint64_t max = std::numeric_limits<uint64_t>::max();
  const uint64_t limit = max - max % n;  // accept [0, limit), a multiple of n
  uint64_t x = (*rng)();
  while (x >= limit) x = (*rng)();
  return x % n;
}

double RequiredHypotheses(double inlier_ratio, double success_probability) {
  if (inlier_ratio >= 1.0) return 0.0;
  if (inlier_ratio <= 0.0) return std::numeric_limits<double>::infinity();
  return std::log(1.0 - success_probability) / std::log(1.0 - inlier_ratio);
}

namespace {

struct Hypothesis {
  int consensus = 0;
  double cost = 0.0;
  int pair = -1;
  std::vector<Candidate> pairs;
};

bool Better(const Hypothesis& a, const Hypothesis& b) {
  if (a.consensus != b.consensus) return a.consensus > b.consensus;
  if (a.cost != b.cost) return a.cost < b.cost;
  return a.pair < b.pair;
}

double Nis(const Eigen::Vector2d& nu, const Eigen::Matrix2d& s) {
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  if (!(det > 0.0)) return std::numeric_limits<double>::infinity();
  return (s(1, 1) * nu(0) * nu(0) - (s(0, 1) + s(1, 0)) * nu(0) * nu(1) +
          s(0, 0) * nu(1) * nu(1)) /
         det;
}

// Judges hypotheses (one pair of the sample space each) against the evaluation set: the
// objects whose predictions a hypothesis must recompute, and their rows in the reduced gain
// (robot pose rows 0-2, the heading drift state entering no prediction; then 2 rows per
// object), are found once; the buffers are reused from one hypothesis to the next.
class HypothesisJudge {
 public:
  HypothesisJudge(const SlamState& state, const std::vector<PointMeasurement>& measurements,
                  const std::vector<ObjectPrediction>& predictions,
                  const std::vector<Candidate>& sample_space,
                  const std::vector<Candidate>& evaluation, const SensorMount& mount,
                  const RansacOptions& options);

  // The hypothesis of sample_space[pair_index] with its consensus and cost.
  Hypothesis Judge(int pair_index);

 private:
  void Involve(int object);
  // The state mean updated with pair h alone (only the involved rows), and from it every
  // involved object's predicted observation and its H P H^T conditioned on the hypothesis.
  // Returns S of the pair.
  Eigen::Matrix2d PredictFromHypothesis(const Candidate& h);
  // The evaluation pairs under inlier_chi2 at the hypothesis (not sharing its measurement or
  // object), each with its cost.
  void FindInliers(const Candidate& h);
  // The hypothesis' own pair, then the inliers one-to-one in increasing cost.
  Hypothesis TakeConsensus(const Candidate& h, int pair_index, const Eigen::Matrix2d& s);

  const SlamState& state_;
  const std::vector<PointMeasurement>& measurements_;
  const std::vector<ObjectPrediction>& predictions_;
  const std::vector<Candidate>& sample_space_;
  const std::vector<Candidate>& evaluation_;
  SensorMount mount_;
  RansacOptions options_;

  std::vector<int> row_of_;  // per object: its first row in the reduced gain (-1: none)
  std::vector<int> involved_;
  std::vector<int> state_index_;  // per row of the reduced gain
  int rows_ = 3;
  Eigen::Matrix<double, Eigen::Dynamic, 2> w_;
  std::vector<Eigen::Vector2d> predicted_;
  std::vector<Eigen::Matrix2d> conditioned_hph_;
  std::vector<Candidate> inliers_;
  std::vector<double> inlier_cost_;  // PairCost of each inlier at the hypothesis' state
  std::vector<size_t> inlier_order_;
  std::vector<uint8_t> measurement_used_;
  std::vector<uint8_t> object_used_;
};

HypothesisJudge::HypothesisJudge(const SlamState& state,
                                 const std::vector<PointMeasurement>& measurements,
                                 const std::vector<ObjectPrediction>& predictions,
                                 const std::vector<Candidate>& sample_space,
                                 const std::vector<Candidate>& evaluation,
                                 const SensorMount& mount, const RansacOptions& options)
    : state_(state),
      measurements_(measurements),
      predictions_(predictions),
      sample_space_(sample_space),
      evaluation_(evaluation),
      mount_(mount),
      options_(options),
      row_of_(static_cast<size_t>(state.num_objects()), -1),
      measurement_used_(measurements.size(), 0),
      object_used_(static_cast<size_t>(state.num_objects()), 0) {
  for (const Candidate& c : sample_space) Involve(c.object);
  for (const Candidate& c : evaluation) Involve(c.object);
  rows_ = 3 + 2 * static_cast<int>(involved_.size());
  state_index_.resize(static_cast<size_t>(rows_));
  for (int r = 0; r < 3; ++r) state_index_[static_cast<size_t>(r)] = r;
  for (size_t k = 0; k < involved_.size(); ++k) {
    const int p = state.object(involved_[k]).position_index;
    state_index_[3 + 2 * k] = p;
    state_index_[3 + 2 * k + 1] = p + 1;
  }
  w_.resize(rows_, 2);
  predicted_.resize(involved_.size());
  conditioned_hph_.resize(involved_.size());
}

void HypothesisJudge::Involve(int object) {
  if (row_of_[static_cast<size_t>(object)] < 0) {
    row_of_[static_cast<size_t>(object)] = 3 + 2 * static_cast<int>(involved_.size());
    involved_.push_back(object);
  }
}

Eigen::Matrix2d HypothesisJudge::PredictFromHypothesis(const Candidate& h) {
  const auto cov = state_.covariance();
  const auto mean = state_.mean();
  const ObjectPrediction& ph = predictions_[static_cast<size_t>(h.object)];
  const PointMeasurement& zh = measurements_[static_cast<size_t>(h.measurement)];
  const int p = state_.object(h.object).position_index;
  // W = P H^T on the involved rows only.
  for (int r = 0; r < rows_; ++r) {
    const int i = state_index_[static_cast<size_t>(r)];
    const Eigen::RowVector3d pr(cov(i, 0), cov(i, 1), cov(i, 2));
    const Eigen::RowVector2d pp(cov(i, p), cov(i, p + 1));
    w_.row(r) = pr * ph.jacobian_robot.transpose() + pp * ph.jacobian_position.transpose();
  }
  const Eigen::Matrix2d s = ph.hph + zh.covariance;
  const Eigen::Matrix2d s_inverse = s.inverse();
  Eigen::Vector2d nu = zh.range_bearing - ph.range_bearing;
  nu(1) = WrapAngle(nu(1));
  const Eigen::Matrix<double, Eigen::Dynamic, 1> delta = w_ * (s_inverse * nu);
  Eigen::Vector3d robot_h = state_.robot_pose() + delta.head<3>();
  robot_h(2) = WrapAngle(robot_h(2));
  for (size_t k = 0; k < involved_.size(); ++k) {
    const int object = involved_[k];
    const ObjectPrediction& pk = predictions_[static_cast<size_t>(object)];
    const Eigen::Vector2d position =
        mean.segment<2>(state_.object(object).position_index) + delta.segment<2>(3 + 2 * k);
    predicted_[k] =
        pk.valid ? PredictRangeBearing(robot_h, position, mount_) : Eigen::Vector2d::Zero();
    const Eigen::Matrix2d g = pk.jacobian_robot * w_.topRows<3>() +
                              pk.jacobian_position * w_.middleRows<2>(3 + 2 * static_cast<int>(k));
    conditioned_hph_[k] = pk.hph - g * s_inverse * g.transpose();
  }
  return s;
}

void HypothesisJudge::FindInliers(const Candidate& h) {
  inliers_.clear();
  inlier_cost_.clear();
  for (const Candidate& c : evaluation_) {
    if (c.measurement == h.measurement || c.object == h.object) continue;
    const size_t k = static_cast<size_t>((row_of_[static_cast<size_t>(c.object)] - 3) / 2);
    if (!predictions_[static_cast<size_t>(c.object)].valid) continue;
    const PointMeasurement& z = measurements_[static_cast<size_t>(c.measurement)];
    Eigen::Vector2d innovation = z.range_bearing - predicted_[k];
    innovation(1) = WrapAngle(innovation(1));
    const Eigen::Matrix2d s_c = conditioned_hph_[k] + z.covariance;
    const double nis = Nis(innovation, s_c);
    if (nis < options_.inlier_chi2) {
      inliers_.push_back({c.measurement, c.object, nis});
      inlier_cost_.push_back(PairCost(nis, s_c));
    }
  }
  inlier_order_.resize(inliers_.size());
  for (size_t k = 0; k < inlier_order_.size(); ++k) inlier_order_[k] = k;
  std::stable_sort(inlier_order_.begin(), inlier_order_.end(),
                   [&](size_t a, size_t b) { return inlier_cost_[a] < inlier_cost_[b]; });
}

Hypothesis HypothesisJudge::TakeConsensus(const Candidate& h, int pair_index,
                                          const Eigen::Matrix2d& s) {
  Hypothesis hypothesis;
  hypothesis.pair = pair_index;
  hypothesis.pairs.push_back(h);
  hypothesis.cost = PairCost(h.nis, s);
  measurement_used_[static_cast<size_t>(h.measurement)] = 1;
  object_used_[static_cast<size_t>(h.object)] = 1;
  for (size_t k : inlier_order_) {
    const Candidate& c = inliers_[k];
    if (measurement_used_[static_cast<size_t>(c.measurement)] ||
        object_used_[static_cast<size_t>(c.object)]) {
      continue;
    }
    measurement_used_[static_cast<size_t>(c.measurement)] = 1;
    object_used_[static_cast<size_t>(c.object)] = 1;
    hypothesis.pairs.push_back(c);
    hypothesis.cost += inlier_cost_[k];
  }
  for (const Candidate& c : hypothesis.pairs) {
    measurement_used_[static_cast<size_t>(c.measurement)] = 0;
    object_used_[static_cast<size_t>(c.object)] = 0;
  }
  hypothesis.consensus = static_cast<int>(hypothesis.pairs.size());
  return hypothesis;
}

Hypothesis HypothesisJudge::Judge(int pair_index) {
  const Candidate& h = sample_space_[static_cast<size_t>(pair_index)];
  const Eigen::Matrix2d s = PredictFromHypothesis(h);
  FindInliers(h);
  return TakeConsensus(h, pair_index, s);
}

}  // namespace

RansacOutcome RunOnePointRansac(const SlamState& state,
                                const std::vector<PointMeasurement>& measurements,
                                const std::vector<ObjectPrediction>& predictions,
                                const std::vector<Candidate>& sample_space,
                                const std::vector<Candidate>& evaluation,
                                const SensorMount& mount, const RansacOptions& options,
                                std::mt19937_64* rng) {
  RansacOutcome outcome;
  if (sample_space.empty()) return outcome;
  HypothesisJudge judge(state, measurements, predictions, sample_space, evaluation, mount,
                        options);
  // Draw without replacement: a partial Fisher-Yates shuffle of the pair indices.
  const int space = static_cast<int>(sample_space.size());
  std::vector<int> order(static_cast<size_t>(space));
  for (int k = 0; k < space; ++k) order[static_cast<size_t>(k)] = k;
  double needed = static_cast<double>(options.max_hypotheses);
  Hypothesis best;
  const int64_t tests_per_hypothesis = static_cast<int64_t>(evaluation.size());
  for (int k = 0; k < space && k < options.max_hypotheses && static_cast<double>(k) < needed;
       ++k) {
    if (k > 0 && outcome.pair_tests + tests_per_hypothesis > options.max_pair_tests) {
      outcome.budget_cut = true;
      break;
    }
    outcome.pair_tests += tests_per_hypothesis;
    const int pick = k + static_cast<int>(UniformIndex(rng, static_cast<uint64_t>(space - k)));
    std::swap(order[static_cast<size_t>(k)], order[static_cast<size_t>(pick)]);
    Hypothesis hypothesis = judge.Judge(order[static_cast<size_t>(k)]);
    ++outcome.hypotheses;
    if (best.pair < 0 || Better(hypothesis, best)) {
      const bool more_consensus = best.pair < 0 || hypothesis.consensus > best.consensus;
      best = std::move(hypothesis);
      if (more_consensus) {
        const double inlier_ratio = static_cast<double>(best.consensus) / space;
        needed = std::min(needed, RequiredHypotheses(inlier_ratio, options.success_probability));
      }
    }
  }
  outcome.consensus = std::move(best.pairs);
  outcome.best_pair = best.pair;
  return outcome;
}

void VisitRansacOptions(OptionVisitor* v, RansacOptions* r) {
  using R = OptionRange;
  v->Double("success_probability", &r->success_probability, R::Open(0, 1),
            "p of eq. 16 (paper: 0.99)");
  v->Int("max_hypotheses", &r->max_hypotheses, R::Between(1, 1000000),
         "cap N of the hypotheses per scan (paper: 1000)");
  v->Int("max_pair_tests", &r->max_pair_tests, R::Between(1, 1e12),
         "cap of hypotheses x evaluation pairs per scan (work of one scan's RANSAC)");
  v->Double("inlier_chi2", &r->inlier_chi2, R::Above(0),
            "consensus threshold on the conditioned NIS (5.99: 95 %)");
}

}  // namespace slammtt
