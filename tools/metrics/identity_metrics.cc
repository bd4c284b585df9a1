#include "tools/metrics/identity_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "tools/metrics/assignment.h"

namespace slammtt {
namespace {

constexpr int kNumAlphas = 19;  // 0.05, 0.10, ..., 0.95 (HOTA paper, section 6)
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

double Alpha(int k) { return 0.05 * (k + 1); }

// Dense indices of the ids seen over the run, in increasing id order.
std::map<int64_t, int> IndexIds(const std::vector<std::vector<IdentifiedPoint>>& frames) {
  std::map<int64_t, int> index;
  for (const auto& frame : frames) {
    for (const IdentifiedPoint& p : frame) index.emplace(p.id, 0);
  }
  int next = 0;
  for (auto& [id, k] : index) k = next++;
  return index;
}

// An assignment that maximises the sum of non-negative `gain` (every pair allowed, so the
// number of pairs is min(rows, cols) and minimising max - gain maximises the gain).
Assignment MaximiseGain(const Eigen::MatrixXd& gain) {
  if (gain.size() == 0) return SolveMinCostAssignment(gain);
  return SolveMinCostAssignment(Eigen::MatrixXd::Constant(gain.rows(), gain.cols(),
                                                          gain.maxCoeff()) -
                                gain);
}

void CheckFrame(const std::vector<IdentifiedPoint>& points) {
  std::set<int64_t> ids;
  for (const IdentifiedPoint& p : points) {
    if (!ids.insert(p.id).second || !p.position_m.allFinite()) {
      throw std::invalid_argument("identity metrics: repeated id or non-finite position");
    }
  }
}

}  // namespace

IdentityMetricsAccumulator::IdentityMetricsAccumulator(double match_threshold_m)
    : threshold_m_(match_threshold_m) {
  if (!(match_threshold_m > 0.0)) {
    throw std::invalid_argument("identity metrics: the match threshold must be positive");
  }
}

void IdentityMetricsAccumulator::AddFrame(const std::vector<IdentifiedPoint>& truth,
                                          const std::vector<IdentifiedPoint>& hypotheses) {
  CheckFrame(truth);
  CheckFrame(hypotheses);
  frames_.push_back({truth, hypotheses});
}

IdentityScores IdentityMetricsAccumulator::Scores() const {
  IdentityScores s;
  s.num_frames = static_cast<int64_t>(frames_.size());
  std::vector<std::vector<IdentifiedPoint>> truth_frames;
  std::vector<std::vector<IdentifiedPoint>> hypothesis_frames;
  for (const Frame& f : frames_) {
    truth_frames.push_back(f.truth);
    hypothesis_frames.push_back(f.hypotheses);
    s.num_truth_detections += static_cast<int64_t>(f.truth.size());
    s.num_hypothesis_detections += static_cast<int64_t>(f.hypotheses.size());
  }
  if (s.num_truth_detections + s.num_hypothesis_detections == 0) return s;
  const std::map<int64_t, int> truth_index = IndexIds(truth_frames);
  const std::map<int64_t, int> hypothesis_index = IndexIds(hypothesis_frames);
  const int num_truth_ids = static_cast<int>(truth_index.size());
  const int num_hypothesis_ids = static_cast<int>(hypothesis_index.size());

  // Per frame: the similarity of every (truth, hypothesis) pair, with dense indices.
  struct Pairs {
    std::vector<int> truth;
    std::vector<int> hypotheses;
    Eigen::MatrixXd similarity;  // max(0, 1 - d / threshold)
  };
  std::vector<Pairs> pairs(frames_.size());
  Eigen::MatrixXd within(num_truth_ids, num_hypothesis_ids);  // IDF1: frames within threshold
  Eigen::MatrixXd potential(num_truth_ids, num_hypothesis_ids);  // HOTA step 1
  within.setZero();
  potential.setZero();
  Eigen::VectorXd truth_frames_present = Eigen::VectorXd::Zero(num_truth_ids);
  Eigen::VectorXd hypothesis_frames_present = Eigen::VectorXd::Zero(num_hypothesis_ids);
  for (size_t t = 0; t < frames_.size(); ++t) {
    const Frame& f = frames_[t];
    Pairs& p = pairs[t];
    for (const IdentifiedPoint& o : f.truth) p.truth.push_back(truth_index.at(o.id));
    for (const IdentifiedPoint& h : f.hypotheses) {
      p.hypotheses.push_back(hypothesis_index.at(h.id));
    }
    p.similarity.resize(static_cast<Eigen::Index>(f.truth.size()),
                        static_cast<Eigen::Index>(f.hypotheses.size()));
    for (size_t i = 0; i < f.truth.size(); ++i) {
      truth_frames_present(p.truth[i]) += 1.0;
      for (size_t j = 0; j < f.hypotheses.size(); ++j) {
        const double d = (f.truth[i].position_m - f.hypotheses[j].position_m).norm();
        p.similarity(i, j) = std::max(0.0, 1.0 - d / threshold_m_);
        if (d <= threshold_m_) within(p.truth[i], p.hypotheses[j]) += 1.0;
      }
    }
    for (int j : p.hypotheses) hypothesis_frames_present(j) += 1.0;
    const Eigen::VectorXd row_sums = p.similarity.rowwise().sum();
    const Eigen::RowVectorXd col_sums = p.similarity.colwise().sum();
    for (Eigen::Index i = 0; i < p.similarity.rows(); ++i) {
      for (Eigen::Index j = 0; j < p.similarity.cols(); ++j) {
        const double denominator = row_sums(i) + col_sums(j) - p.similarity(i, j);
        if (denominator > kEpsilon) {
          potential(p.truth[i], p.hypotheses[j]) += p.similarity(i, j) / denominator;
        }
      }
    }
  }

  // IDF1: one global bipartite matching of trajectories.
  const Assignment global = MaximiseGain(within);
  for (int i = 0; i < num_truth_ids; ++i) {
    const int j = global.row_to_col.empty() ? -1 : global.row_to_col[i];
    if (j >= 0) s.id_true_positives += static_cast<int64_t>(within(i, j));
  }
  s.id_false_negatives = s.num_truth_detections - s.id_true_positives;
  s.id_false_positives = s.num_hypothesis_detections - s.id_true_positives;
  const double idtp = static_cast<double>(s.id_true_positives);
  s.idf1 = 2.0 * idtp /
           static_cast<double>(s.num_truth_detections + s.num_hypothesis_detections);
  if (s.num_hypothesis_detections > 0) {
    s.id_precision = idtp / static_cast<double>(s.num_hypothesis_detections);
  }
  if (s.num_truth_detections > 0) {
    s.id_recall = idtp / static_cast<double>(s.num_truth_detections);
  }

  // HOTA steps 1-3.
  Eigen::MatrixXd alignment(num_truth_ids, num_hypothesis_ids);
  for (int i = 0; i < num_truth_ids; ++i) {
    for (int j = 0; j < num_hypothesis_ids; ++j) {
      alignment(i, j) = potential(i, j) / (truth_frames_present(i) +
                                           hypothesis_frames_present(j) - potential(i, j));
    }
  }
  std::array<double, kNumAlphas> true_positives{};
  std::array<double, kNumAlphas> false_negatives{};
  std::array<double, kNumAlphas> false_positives{};
  std::array<double, kNumAlphas> localisation_sum{};
  std::array<std::map<std::pair<int, int>, double>, kNumAlphas> matches{};
  for (const Pairs& p : pairs) {
    const Eigen::Index rows = p.similarity.rows();
    const Eigen::Index cols = p.similarity.cols();
    Eigen::MatrixXd score(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index j = 0; j < cols; ++j) {
        score(i, j) = alignment(p.truth[i], p.hypotheses[j]) * p.similarity(i, j);
      }
    }
    const Assignment frame = MaximiseGain(score);
    for (int a = 0; a < kNumAlphas; ++a) {
      int matched = 0;
      for (Eigen::Index i = 0; i < rows; ++i) {
        const int j = frame.row_to_col.empty() ? -1 : frame.row_to_col[i];
        if (j < 0 || p.similarity(i, j) < Alpha(a) - kEpsilon) continue;
        ++matched;
        localisation_sum[a] += p.similarity(i, j);
        matches[a][{p.truth[i], p.hypotheses[j]}] += 1.0;
      }
      true_positives[a] += matched;
      false_negatives[a] += static_cast<double>(rows - matched);
      false_positives[a] += static_cast<double>(cols - matched);
    }
  }
  double hota = 0.0;
  double det_a = 0.0;
  double ass_a = 0.0;
  double loc_a = 0.0;
  for (int a = 0; a < kNumAlphas; ++a) {
    double association = 0.0;
    for (const auto& [pair, count] : matches[a]) {
      association += count * count /
                     (truth_frames_present(pair.first) +
                      hypothesis_frames_present(pair.second) - count);
    }
    const double tp = true_positives[a];
    const double alpha_ass = association / std::max(1.0, tp);
    const double alpha_det = tp / std::max(1.0, tp + false_negatives[a] + false_positives[a]);
    hota += std::sqrt(alpha_det * alpha_ass);
    det_a += alpha_det;
    ass_a += alpha_ass;
    loc_a += std::max(1e-10, localisation_sum[a]) / std::max(1e-10, tp);
  }
  s.hota = hota / kNumAlphas;
  s.det_a = det_a / kNumAlphas;
  s.ass_a = ass_a / kNumAlphas;
  s.loc_a = loc_a / kNumAlphas;
  return s;
}

}  // namespace slammtt
