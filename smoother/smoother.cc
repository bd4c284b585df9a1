#include "smoother/smoother.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/angle.h"
#include "common/checked_options.h"
#include "smoother/factors.h"
#include "geometry/pose2.h"

namespace slammtt {

namespace {

enum class FactorKind { kOdometry, kRangeBearing, kRelativePosition, kPosePrior, kPointPrior };

constexpr int kPoseDim = 3;
constexpr int kLandmarkDim = 2;

}  // namespace

struct Smoother::Variable {
  bool is_pose = true;
  int newest_factor_update = 0;  // the update count when its newest factor arrived
  int64_t id = 0;
  int dim = kPoseDim;
  Eigen::Vector3d linearization = Eigen::Vector3d::Zero();  // (x, y[, theta])
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();          // pending step from it
  int offset = -1;         // first scalar in the system, -1 outside it
  bool alive = true;       // false once removed
  bool in_system = false;  // part of the kept factor / the layout
  std::vector<int> factors;
};

struct Smoother::Factor {
  FactorKind kind = FactorKind::kOdometry;
  int variables[2] = {-1, -1};
  int num_variables = 1;
  int rows = 3;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
  Eigen::Matrix3d root = Eigen::Matrix3d::Zero();  // U, Lambda = U^T U (rows x rows)
  SensorMount mount;
  // Whitened residual and Jacobians at the variables' linearisation points.
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  Eigen::Matrix3d jacobian[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  bool alive = true;
  bool in_system = false;
  // Where the factor's blocks of J^T J sit in the layout's columns: row offsets of each
  // variable's diagonal block and of the off-diagonal block (lower offset in the higher's).
  int diagonal_row[2] = {0, 0};
  int cross_row = 0;
};

// The pattern of the upper triangle of J^T J over the variables in the system (compressed
// columns), in scalar offsets; free slots at the end hold identity diagonals.
struct Smoother::Layout {
  int n = 0;
  int free_begin = 0;
  std::vector<int> column_starts;
  std::vector<int> rows;
};

namespace {

// Unwhitened residual and Jacobians (rows x dim of each variable, top-left blocks) of a factor
// at the variables' values a (and b). The one place that maps a factor kind to factors.h.
template <typename FactorT>
Eigen::Vector3d EvaluateFactor(const FactorT& f, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, Eigen::Matrix3d* jacobian_a,
                               Eigen::Matrix3d* jacobian_b) {
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  switch (f.kind) {
    case FactorKind::kOdometry:
      residual = OdometryResidual(a, b, f.measured, jacobian_a, jacobian_b);
      break;
    case FactorKind::kRangeBearing:
    case FactorKind::kRelativePosition: {
      Eigen::Matrix<double, 2, 3> pose_jacobian;
      Eigen::Matrix2d point_jacobian;
      const bool jacobians = jacobian_a != nullptr;
      const Eigen::Vector2d point = b.head<2>();
      const Eigen::Vector2d measured = f.measured.template head<2>();
      const Eigen::Vector2d r =
          f.kind == FactorKind::kRangeBearing
              ? RangeBearingResidual(a, point, measured, f.mount,
                                     jacobians ? &pose_jacobian : nullptr,
                                     jacobians ? &point_jacobian : nullptr)
              : RelativePositionResidual(a, point, measured,
                                         jacobians ? &pose_jacobian : nullptr,
                                         jacobians ? &point_jacobian : nullptr);
      residual.head<2>() = r;
      if (jacobians) {
        jacobian_a->topRows<2>() = pose_jacobian;
        jacobian_b->topLeftCorner<2, 2>() = point_jacobian;
      }
      break;
    }
    case FactorKind::kPosePrior:
      residual = PosePriorResidual(a, f.measured, jacobian_a);
      break;
    case FactorKind::kPointPrior: {
      Eigen::Matrix2d point_jacobian;
      residual.head<2>() = PointPriorResidual(a.head<2>(), f.measured.template head<2>(),
                                              jacobian_a != nullptr ? &point_jacobian : nullptr);
      if (jacobian_a != nullptr) jacobian_a->topLeftCorner<2, 2>() = point_jacobian;
      break;
    }
  }
  return residual;
}

std::optional<std::string> CheckFinite(const Eigen::MatrixXd& value, const char* what) {
  if (!value.allFinite()) return std::string(what) + " has a non-finite entry";
  return std::nullopt;
}

}  // namespace

void VisitSmootherOptions(OptionVisitor* v, SmootherOptions* o) {
  using R = OptionRange;
  constexpr double kMaxCount = 1e9;  // counts stay within int
  int pose_update = static_cast<int>(o->pose_update);
  v->Choice("pose_update", &pose_update, {"additive", "exponential"},
            "a step moves a pose by adding to (x, y, theta), or by pose * exp(step) as GTSAM's "
            "Pose2 retraction");
  o->pose_update = static_cast<SmootherOptions::PoseUpdate>(pose_update);
  int method = static_cast<int>(o->method);
  v->Choice("method", &method, {"gauss_newton", "levenberg_marquardt"}, "batch solver");
  o->method = static_cast<SmootherOptions::Method>(method);
  int damping = static_cast<int>(o->damping);
  v->Choice("damping", &damping, {"identity", "diagonal"},
            "LM adds lambda I (GTSAM's default) or lambda diag(J^T J)");
  o->damping = static_cast<SmootherOptions::Damping>(damping);
  v->Int("max_iterations", &o->max_iterations, R::Between(1, kMaxCount),
         "batch: accepted steps at most");
  v->Double("relative_tolerance", &o->relative_tolerance, R::AtLeast(0),
            "converged when an accepted step lowers chi^2 by less than this fraction of it");
  v->Double("absolute_tolerance", &o->absolute_tolerance, R::AtLeast(0),
            "... or by less than this (chi^2 units)");
  v->Double("initial_lambda", &o->initial_lambda, R::Above(0),
            "LM's first damping (GTSAM's lambdaInitial)");
  v->Double("lambda_factor", &o->lambda_factor, R::Above(1),
            "LM divides lambda by it after a success, multiplies it after a failure "
            "(lambdaFactor)");
  v->Double("max_lambda", &o->max_lambda, R::Above(0),
            "LM stops when lambda would exceed it (lambdaUpperBound)");
  v->Double("min_model_fidelity", &o->min_model_fidelity, R{0.0, 1.0, true, false},
            "a step is accepted above this fraction of the decrease the model predicts "
            "(minModelFidelity)");
  v->Double("relinearize_threshold", &o->relinearize_threshold, R::AtLeast(0),
            "incremental: a variable whose step exceeds it in any component (m or rad) moves its "
            "linearisation point (ISAM2's default)");
  v->Int("relinearize_skip", &o->relinearize_skip, R::Between(1, kMaxCount),
         "incremental: relinearisation is looked at every this many updates (ISAM2's default)");
  v->Int("max_incremental_relinearizations", &o->max_incremental_relinearizations,
         R::Between(0, kMaxCount),
         "more variables to relinearise at once: a full refactorisation instead of rank updates");
  v->Int("full_relinearization_interval", &o->full_relinearization_interval,
         R::Between(0, kMaxCount), "updates between full relinearisations (0: never)");
  v->Double("reorder_fill_ratio", &o->reorder_fill_ratio, R::AtLeast(1),
            "refactorise when the factor's nonzeros grew this much since the ordering");
  v->Double("max_update_work_share", &o->max_update_work_share, R::AtLeast(0),
            "incremental: an update whose rank updates would cost more than this share of a "
            "factorisation afresh (counted from the factor's structure) refactorises instead "
            "(0: never)");
  v->Int("min_free_slots", &o->min_free_slots, R::Between(0, kMaxCount),
         "variables' room reserved at the end of the ordering (at least a quarter of the live "
         "ones)");
  v->Int("ordering_recent_updates", &o->ordering_recent_updates, R::Between(0, kMaxCount),
         "incremental: a refactorisation orders the variables of factors added in this many last "
         "updates after the others (constrained minimum degree, as ISAM2; 0: CHOLMOD's ordering)");
  v->Bool("update_chi_square", &o->update_chi_square,
          "incremental: each update reports chi^2 (a pass over every factor; false: not "
          "computed, as ISAM2's update() by default)");
}

std::string CheckSmootherOptions(const SmootherOptions& options) {
  SmootherOptions o = options;
  OptionRangeCheck check;
  VisitSmootherOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  if (!(o.max_lambda >= o.initial_lambda)) return "max_lambda must be >= initial_lambda";
  return "";
}

Smoother::Smoother(const SmootherOptions& options)
    : options_(CheckedOptions(options, &CheckSmootherOptions, "smoother options")),
      layout_(std::make_unique<Layout>()),
      cholesky_(std::make_unique<SparseCholesky>()) {}

Smoother::~Smoother() = default;

// ---- building the problem ----

std::optional<std::string> Smoother::AddVariable(bool is_pose, int64_t id,
                                                 const Eigen::Vector3d& value) {
  auto& index = is_pose ? pose_index_ : landmark_index_;
  const char* kind = is_pose ? "pose" : "landmark";
  if (index.count(id) != 0) return std::string(kind) + " " + std::to_string(id) + " exists";
  if (!value.allFinite()) {
    return std::string(kind) + " " + std::to_string(id) + ": initial value is not finite";
  }
  Variable variable;
  variable.is_pose = is_pose;
  variable.id = id;
  variable.dim = is_pose ? kPoseDim : kLandmarkDim;
  variable.linearization = value;
  if (is_pose) variable.linearization(2) = WrapAngle(value(2));
  index.emplace(id, static_cast<int>(variables_.size()));
  pending_variables_.push_back(static_cast<int>(variables_.size()));
  component_parent_.push_back(static_cast<int>(variables_.size()));
  component_anchored_.push_back(0);
  ++unanchored_components_;
  ++live_variables_;
  variables_.push_back(std::move(variable));
  marginal_factor_valid_ = false;
  return std::nullopt;
}

std::optional<std::string> Smoother::AddPose(PoseId id, const Eigen::Vector3d& initial_pose) {
  return AddVariable(true, id, initial_pose);
}

std::optional<std::string> Smoother::AddLandmark(LandmarkId id,
                                                 const Eigen::Vector2d& initial_position) {
  return AddVariable(false, id, Eigen::Vector3d(initial_position(0), initial_position(1), 0.0));
}

std::optional<std::string> Smoother::RemoveLandmark(LandmarkId id) {
  const auto found = landmark_index_.find(id);
  if (found == landmark_index_.end()) return "landmark " + std::to_string(id) + " is unknown";
  Variable& landmark = variables_[found->second];
  landmark.alive = false;
  for (int f : landmark.factors) factors_[f].alive = false;
  landmark_index_.erase(found);
  --live_variables_;
  components_stale_ = true;  // a removal can split a part: rebuilt at the next check
  // In the kept factor, the next Update takes its factors out by rank downdates (its slot stays,
  // an isolated identity, until the next re-ordering); a landmark not in it yet needs nothing.
  if (landmark.in_system) removed_in_system_.push_back(found->second);
  marginal_factor_valid_ = false;
  return std::nullopt;
}

std::optional<std::string> Smoother::AddFactor(Factor factor) {
  for (int k = 0; k < factor.num_variables; ++k) {
    variables_[factor.variables[k]].factors.push_back(static_cast<int>(factors_.size()));
    variables_[factor.variables[k]].newest_factor_update = updates_;
  }
  pending_factors_.push_back(static_cast<int>(factors_.size()));
  if (!components_stale_) JoinComponents(factor);
  factors_.push_back(std::move(factor));
  marginal_factor_valid_ = false;
  return std::nullopt;
}

namespace {

template <typename Map>
std::optional<int> Find(const Map& index, int64_t id) {
  const auto found = index.find(id);
  if (found == index.end()) return std::nullopt;
  return found->second;
}

}  // namespace

std::optional<std::string> Smoother::AddOdometry(PoseId from, PoseId to,
                                                 const Eigen::Vector3d& relative,
                                                 const Eigen::Matrix3d& information) {
  const std::string what = "odometry " + std::to_string(from) + "->" + std::to_string(to);
  const auto i = Find(pose_index_, from);
  const auto j = Find(pose_index_, to);
  if (!i || !j) return what + ": unknown pose " + std::to_string(!i ? from : to);
  if (*i == *j) return what + ": a pose related to itself";
  if (auto error = CheckFinite(relative, "relative pose")) return what + ": " + *error;
  Factor factor;
  if (auto error = SquareRootInformation<3>(information, &factor.root)) {
    return what + ": " + *error;
  }
  factor.kind = FactorKind::kOdometry;
  factor.variables[0] = *i;
  factor.variables[1] = *j;
  factor.num_variables = 2;
  factor.rows = 3;
  factor.measured = relative;
  factor.measured(2) = WrapAngle(relative(2));
  return AddFactor(std::move(factor));
}

namespace {

// Shared checks of the two pose-landmark factors.
std::optional<std::string> PointFactorError(const std::optional<int>& pose,
                                            const std::optional<int>& landmark, PoseId pose_id,
                                            LandmarkId landmark_id) {
  if (!pose) return "unknown pose " + std::to_string(pose_id);
  if (!landmark) return "unknown landmark " + std::to_string(landmark_id);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> Smoother::AddRangeBearing(PoseId pose, LandmarkId landmark,
                                                     const Eigen::Vector2d& range_bearing,
                                                     const Eigen::Matrix2d& information,
                                                     const SensorMount& mount) {
  const std::string what =
      "range-bearing " + std::to_string(pose) + "->" + std::to_string(landmark);
  const auto p = Find(pose_index_, pose);
  const auto l = Find(landmark_index_, landmark);
  if (auto error = PointFactorError(p, l, pose, landmark)) return what + ": " + *error;
  if (auto error = CheckFinite(range_bearing, "measurement")) return what + ": " + *error;
  if (!(range_bearing(0) > 0.0)) return what + ": range is not positive";
  if (!std::isfinite(mount.forward_m) || !std::isfinite(mount.left_m)) {
    return what + ": mount offset is not finite";
  }
  Factor factor;
  Eigen::Matrix2d root;
  if (auto error = SquareRootInformation<2>(information, &root)) return what + ": " + *error;
  factor.root.topLeftCorner<2, 2>() = root;
  factor.kind = FactorKind::kRangeBearing;
  factor.variables[0] = *p;
  factor.variables[1] = *l;
  factor.num_variables = 2;
  factor.rows = 2;
  factor.measured << range_bearing(0), WrapAngle(range_bearing(1)), 0.0;
  factor.mount = mount;
  return AddFactor(std::move(factor));
}

std::optional<std::string> Smoother::AddRelativePosition(PoseId pose, LandmarkId landmark,
                                                         const Eigen::Vector2d& position_in_pose,
                                                         const Eigen::Matrix2d& information) {
  const std::string what =
      "relative position " + std::to_string(pose) + "->" + std::to_string(landmark);
  const auto p = Find(pose_index_, pose);
  const auto l = Find(landmark_index_, landmark);
  if (auto error = PointFactorError(p, l, pose, landmark)) return what + ": " + *error;
  if (auto error = CheckFinite(position_in_pose, "measurement")) return what + ": " + *error;
  Factor factor;
  Eigen::Matrix2d root;
  if (auto error = SquareRootInformation<2>(information, &root)) return what + ": " + *error;
  factor.root.topLeftCorner<2, 2>() = root;
  factor.kind = FactorKind::kRelativePosition;
  factor.variables[0] = *p;
  factor.variables[1] = *l;
  factor.num_variables = 2;
  factor.rows = 2;
  factor.measured << position_in_pose(0), position_in_pose(1), 0.0;
  return AddFactor(std::move(factor));
}

std::optional<std::string> Smoother::AddPosePrior(PoseId pose, const Eigen::Vector3d& prior,
                                                  const Eigen::Matrix3d& information) {
  const std::string what = "pose prior " + std::to_string(pose);
  const auto p = Find(pose_index_, pose);
  if (!p) return what + ": unknown pose " + std::to_string(pose);
  if (auto error = CheckFinite(prior, "prior")) return what + ": " + *error;
  Factor factor;
  if (auto error = SquareRootInformation<3>(information, &factor.root)) {
    return what + ": " + *error;
  }
  factor.kind = FactorKind::kPosePrior;
  factor.variables[0] = *p;
  factor.num_variables = 1;
  factor.rows = 3;
  factor.measured = prior;
  factor.measured(2) = WrapAngle(prior(2));
  return AddFactor(std::move(factor));
}

std::optional<std::string> Smoother::AddPointPrior(LandmarkId landmark,
                                                   const Eigen::Vector2d& prior,
                                                   const Eigen::Matrix2d& information) {
  const std::string what = "point prior " + std::to_string(landmark);
  const auto l = Find(landmark_index_, landmark);
  if (!l) return what + ": unknown landmark " + std::to_string(landmark);
  if (auto error = CheckFinite(prior, "prior")) return what + ": " + *error;
  Factor factor;
  Eigen::Matrix2d root;
  if (auto error = SquareRootInformation<2>(information, &root)) return what + ": " + *error;
  factor.root.topLeftCorner<2, 2>() = root;
  factor.kind = FactorKind::kPointPrior;
  factor.variables[0] = *l;
  factor.num_variables = 1;
  factor.rows = 2;
  factor.measured << prior(0), prior(1), 0.0;
  return AddFactor(std::move(factor));
}

std::optional<std::string> Smoother::SetPoseEstimate(PoseId id, const Eigen::Vector3d& pose) {
  const auto index = Find(pose_index_, id);
  if (!index) return "pose " + std::to_string(id) + " is unknown";
  if (!pose.allFinite()) return "pose " + std::to_string(id) + ": estimate is not finite";
  Variable& variable = variables_[*index];
  variable.linearization = pose;
  variable.linearization(2) = WrapAngle(pose(2));
  variable.delta.setZero();
  needs_refactorization_ = true;
  marginal_factor_valid_ = false;
  return std::nullopt;
}

std::optional<std::string> Smoother::SetLandmarkEstimate(LandmarkId id,
                                                         const Eigen::Vector2d& position) {
  const auto index = Find(landmark_index_, id);
  if (!index) return "landmark " + std::to_string(id) + " is unknown";
  if (!position.allFinite()) return "landmark " + std::to_string(id) + ": not finite";
  Variable& variable = variables_[*index];
  variable.linearization << position(0), position(1), 0.0;
  variable.delta.setZero();
  needs_refactorization_ = true;
  marginal_factor_valid_ = false;
  return std::nullopt;
}

// ---- evaluation ----

Eigen::Vector3d Smoother::Estimate(const Variable& variable) const {
  if (variable.is_pose) {
    return options_.pose_update == SmootherOptions::PoseUpdate::kExponential
               ? RetractPoseExponential(variable.linearization, variable.delta)
               : RetractPose(variable.linearization, variable.delta);
  }
  Eigen::Vector3d point = variable.linearization + variable.delta;
  point(2) = 0.0;
  return point;
}

double Smoother::FactorChiSquare(const Factor& f, bool at_linearization_point) const {
  const Variable& a = variables_[f.variables[0]];
  const Eigen::Vector3d value_a = at_linearization_point ? a.linearization : Estimate(a);
  Eigen::Vector3d value_b = Eigen::Vector3d::Zero();
  if (f.num_variables == 2) {
    const Variable& b = variables_[f.variables[1]];
    value_b = at_linearization_point ? b.linearization : Estimate(b);
  }
  const Eigen::Vector3d r = EvaluateFactor(f, value_a, value_b, nullptr, nullptr);
  const int m = f.rows;
  const Eigen::VectorXd whitened =
      f.root.topLeftCorner(m, m).triangularView<Eigen::Upper>() * r.head(m);
  return whitened.squaredNorm();
}

double Smoother::ChiSquare() const {
  double total = 0.0;
  for (const Factor& f : factors_) {
    if (f.alive) total += FactorChiSquare(f, false);
  }
  return total;
}

double Smoother::LinearizedChiSquare() const {
  double total = 0.0;
  for (const Factor& f : factors_) {
    if (!f.alive) continue;
    // Rows past f.rows and columns past a variable's dim are zero (Linearize).
    Eigen::Vector3d linear = f.residual;
    for (int k = 0; k < f.num_variables; ++k) {
      linear += f.jacobian[k] * variables_[f.variables[k]].delta;
    }
    total += linear.squaredNorm();
  }
  return total;
}

void Smoother::Linearize(Factor* f) const {
  const Variable& a = variables_[f->variables[0]];
  const Eigen::Vector3d value_b =
      f->num_variables == 2 ? variables_[f->variables[1]].linearization : Eigen::Vector3d::Zero();
  Eigen::Matrix3d jacobian_a = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d jacobian_b = Eigen::Matrix3d::Zero();
  const Eigen::Vector3d r = EvaluateFactor(*f, a.linearization, value_b, &jacobian_a, &jacobian_b);
  if (options_.pose_update == SmootherOptions::PoseUpdate::kExponential) {
    // The steps are taken in each pose's own frame: chain the retraction's Jacobian.
    if (a.is_pose) jacobian_a = jacobian_a * RetractionJacobianAtZero(a.linearization(2));
    if (f->num_variables == 2 && variables_[f->variables[1]].is_pose) {
      jacobian_b = jacobian_b * RetractionJacobianAtZero(value_b(2));
    }
  }
  const Eigen::Matrix3d upper = f->root.triangularView<Eigen::Upper>();
  f->residual = upper * r;
  f->jacobian[0] = upper * jacobian_a;
  f->jacobian[1] = upper * jacobian_b;
}

void Smoother::RelinearizeAll() {
  for (Variable& v : variables_) {
    if (!v.alive) continue;
    v.linearization = Estimate(v);
    v.delta.setZero();
  }
}

int Smoother::ComponentRoot(int variable) {
  int v = variable;
  while (component_parent_[v] != v) {
    v = component_parent_[v] = component_parent_[component_parent_[v]];  // path halving
  }
  return v;
}

void Smoother::JoinComponents(const Factor& factor) {
  const int a = ComponentRoot(factor.variables[0]);
  if (factor.num_variables == 1) {
    if (!component_anchored_[a]) {
      component_anchored_[a] = 1;
      --unanchored_components_;
    }
    return;
  }
  const int b = ComponentRoot(factor.variables[1]);
  if (a == b) return;
  unanchored_components_ -= (component_anchored_[a] ? 0 : 1) + (component_anchored_[b] ? 0 : 1);
  component_parent_[a] = b;
  component_anchored_[b] = component_anchored_[a] || component_anchored_[b];
  if (!component_anchored_[b]) ++unanchored_components_;
}

void Smoother::RebuildComponents() {
  const int n = static_cast<int>(variables_.size());
  component_parent_.resize(n);
  std::iota(component_parent_.begin(), component_parent_.end(), 0);
  component_anchored_.assign(n, 0);
  unanchored_components_ = 0;
  for (const Variable& v : variables_) unanchored_components_ += v.alive ? 1 : 0;
  for (const Factor& f : factors_) {
    if (f.alive) JoinComponents(f);
  }
  components_stale_ = false;
}

std::optional<std::string> Smoother::CheckAnchored() {
  if (components_stale_) RebuildComponents();
  if (live_variables_ == 0) return std::string("nothing to solve: no variables");
  if (unanchored_components_ == 0) return std::nullopt;
  // A part without a prior is free to move as a whole: name one of its variables.
  for (int v = 0; v < static_cast<int>(variables_.size()); ++v) {
    if (!variables_[v].alive || component_anchored_[ComponentRoot(v)]) continue;
    return std::string("unconstrained problem: ") +
           (variables_[v].is_pose ? "pose " : "landmark ") + std::to_string(variables_[v].id) +
           " is in a part of the graph without a prior (add a pose or point prior)";
  }
  return std::nullopt;
}

// ---- the normal equations ----

void Smoother::BuildLayout(int free_scalars) {
  Layout& layout = *layout_;
  int offset = 0;
  for (Variable& v : variables_) {
    v.offset = -1;
    v.in_system = false;
    if (!v.alive) continue;
    v.offset = offset;
    v.in_system = true;
    offset += v.dim;
  }
  pending_variables_.clear();
  pending_factors_.clear();
  removed_in_system_.clear();
  layout.free_begin = offset;
  layout.n = offset + free_scalars;
  next_free_offset_ = offset;

  // Lower neighbours (by offset) of every variable, itself last.
  const int num_variables = static_cast<int>(variables_.size());
  std::vector<std::vector<int>> lower(num_variables);
  for (Factor& f : factors_) {
    f.in_system = f.alive;
    if (!f.alive || f.num_variables != 2) continue;
    int a = f.variables[0];
    int b = f.variables[1];
    if (variables_[a].offset > variables_[b].offset) std::swap(a, b);
    lower[b].push_back(a);
  }
  layout.column_starts.assign(layout.n + 1, 0);
  layout.rows.clear();
  // Row offset of neighbour u within v's columns, found by binary search in sorted_lower.
  std::vector<std::vector<int>> sorted_lower(num_variables);
  std::vector<std::vector<int>> row_offsets(num_variables);
  for (int v = 0; v < num_variables; ++v) {
    const Variable& variable = variables_[v];
    if (!variable.alive) continue;
    std::vector<int>& neighbours = lower[v];
    std::sort(neighbours.begin(), neighbours.end(), [this](int x, int y) {
      return variables_[x].offset < variables_[y].offset;
    });
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    int row_offset = 0;
    for (int u : neighbours) {
      row_offsets[v].push_back(row_offset);
      row_offset += variables_[u].dim;
    }
    row_offsets[v].push_back(row_offset);  // the diagonal block
    sorted_lower[v] = neighbours;
    for (int j = 0; j < variable.dim; ++j) {
      const int column = variable.offset + j;
      layout.column_starts[column] = static_cast<int>(layout.rows.size());
      for (int u : neighbours) {
        for (int i = 0; i < variables_[u].dim; ++i) layout.rows.push_back(variables_[u].offset + i);
      }
      for (int i = 0; i <= j; ++i) layout.rows.push_back(variable.offset + i);
    }
  }
  for (int column = layout.free_begin; column < layout.n; ++column) {
    layout.column_starts[column] = static_cast<int>(layout.rows.size());
    layout.rows.push_back(column);
  }
  layout.column_starts[layout.n] = static_cast<int>(layout.rows.size());

  const auto row_offset_of = [&](int u, int v) {
    const auto& neighbours = sorted_lower[v];
    const auto at = std::lower_bound(
        neighbours.begin(), neighbours.end(), u,
        [this](int x, int y) { return variables_[x].offset < variables_[y].offset; });
    return row_offsets[v][at - neighbours.begin()];
  };
  for (Factor& f : factors_) {
    if (!f.alive) continue;
    for (int k = 0; k < f.num_variables; ++k) {
      const int v = f.variables[k];
      f.diagonal_row[k] = row_offsets[v].back();
    }
    if (f.num_variables == 2) {
      int a = f.variables[0];
      int b = f.variables[1];
      if (variables_[a].offset > variables_[b].offset) std::swap(a, b);
      f.cross_row = row_offset_of(a, b);
    }
  }
}

void Smoother::AssembleNormalEquations(std::vector<double>* values,
                                       Eigen::VectorXd* gradient) const {
  const Layout& layout = *layout_;
  values->assign(layout.rows.size(), 0.0);
  gradient->setZero(layout.n);
  for (int column = layout.free_begin; column < layout.n; ++column) {
    (*values)[layout.column_starts[column]] = 1.0;  // free slots: identity
  }
  double* x = values->data();
  const int* starts = layout.column_starts.data();
  for (const Factor& f : factors_) {
    if (!f.alive) continue;
    const int m = f.rows;
    for (int k = 0; k < f.num_variables; ++k) {
      const Variable& v = variables_[f.variables[k]];
      const auto jacobian = f.jacobian[k].topLeftCorner(m, v.dim);
      gradient->segment(v.offset, v.dim) += jacobian.transpose() * f.residual.head(m);
      const Eigen::Matrix3d block = f.jacobian[k].transpose() * f.jacobian[k];
      for (int j = 0; j < v.dim; ++j) {
        double* column = x + starts[v.offset + j] + f.diagonal_row[k];
        for (int i = 0; i <= j; ++i) column[i] += block(i, j);
      }
    }
    if (f.num_variables == 2) {
      int low = 0;
      int high = 1;
      if (variables_[f.variables[0]].offset > variables_[f.variables[1]].offset) {
        std::swap(low, high);
      }
      const Variable& u = variables_[f.variables[low]];
      const Variable& v = variables_[f.variables[high]];
      const Eigen::Matrix3d block = f.jacobian[low].transpose() * f.jacobian[high];
      for (int j = 0; j < v.dim; ++j) {
        double* column = x + starts[v.offset + j] + f.cross_row;
        for (int i = 0; i < u.dim; ++i) column[i] += block(i, j);
      }
    }
  }
}

void Smoother::AppendFactorColumns(const Factor& f,
                                   std::vector<SparseCholesky::SparseColumn>* columns) const {
  for (int row = 0; row < f.rows; ++row) {
    SparseCholesky::SparseColumn column;
    for (int k = 0; k < f.num_variables; ++k) {
      const Variable& v = variables_[f.variables[k]];
      for (int i = 0; i < v.dim; ++i) {
        column.rows.push_back(v.offset + i);
        column.values.push_back(f.jacobian[k](row, i));
      }
    }
    columns->push_back(std::move(column));
  }
}

// ---- batch ----

SolveReport Smoother::Optimize() {
  SolveReport report;
  if (auto error = CheckAnchored()) {
    report.error = *error;
    return report;
  }
  incremental_ready_ = false;
  marginal_factor_valid_ = false;
  RelinearizeAll();
  BuildLayout(0);
  const Layout& layout = *layout_;
  if (!cholesky_->Analyze(layout.n, layout.column_starts, layout.rows,
                          SparseCholesky::Form::kSupernodal)) {
    report.error = "CHOLMOD could not analyse the normal equations";
    return report;
  }
  double chi_square = ChiSquare();
  report.initial_chi_square = chi_square;
  const bool levenberg = options_.method == SmootherOptions::Method::kLevenbergMarquardt;
  double lambda = levenberg ? options_.initial_lambda : 0.0;
  std::vector<double> values;
  std::vector<double> damped;
  Eigen::VectorXd gradient;
  std::vector<int> diagonal_positions(layout.n);
  for (int c = 0; c < layout.n; ++c) diagonal_positions[c] = layout.column_starts[c + 1] - 1;

  for (int outer = 0; outer < options_.max_iterations && !report.converged; ++outer) {
    for (Factor& f : factors_) {
      if (f.alive) Linearize(&f);
    }
    AssembleNormalEquations(&values, &gradient);
    bool accepted = false;
    bool diverged = false;
    while (!accepted) {
      damped = values;
      for (int c = 0; c < layout.n; ++c) {
        const double d = options_.damping == SmootherOptions::Damping::kDiagonal
                             ? std::max(values[diagonal_positions[c]], 1e-6)
                             : 1.0;
        damped[diagonal_positions[c]] += lambda * d;
      }
      ++report.iterations;
      if (!cholesky_->Factorize(damped)) {
        if (!levenberg) {
          report.error = "normal equations not positive definite (unconstrained problem?)";
          report.chi_square = chi_square;
          return report;
        }
        lambda *= options_.lambda_factor;
        if (lambda > options_.max_lambda) break;
        continue;
      }
      const Eigen::VectorXd step = cholesky_->Solve(-gradient);
      if (step.size() != layout.n || !step.allFinite()) {
        report.error = "CHOLMOD solve failed";
        report.chi_square = chi_square;
        return report;
      }
      for (Variable& v : variables_) {
        if (v.alive) v.delta.head(v.dim) = step.segment(v.offset, v.dim);
      }
      const double candidate = ChiSquare();
      const double predicted_decrease = chi_square - LinearizedChiSquare();
      const double decrease = chi_square - candidate;
      // GTSAM's test: the model's fidelity (actual / predicted decrease) above the minimum, or
      // a predicted decrease at rounding level taken as success.
      const bool successful =
          predicted_decrease > std::numeric_limits<double>::epsilon() * chi_square
              ? decrease > options_.min_model_fidelity * predicted_decrease
              : decrease >= 0.0;
      if (!levenberg || successful) {
        accepted = true;
        RelinearizeAll();
        chi_square = candidate;
        lambda /= options_.lambda_factor;
        if (decrease < 0.0) {
          // Gauss-Newton made it worse: stop; converged if only by rounding (chi^2 at the
          // level of 1e-12 of where it started, as with exact measurements).
          report.converged = -decrease <= options_.relative_tolerance * chi_square +
                                              1e-12 * report.initial_chi_square;
          diverged = true;
          break;
        }
        if (decrease <= options_.relative_tolerance * chi_square ||
            decrease <= options_.absolute_tolerance) {
          report.converged = true;
        }
      } else {
        for (Variable& v : variables_) v.delta.setZero();
        lambda *= options_.lambda_factor;
        if (lambda > options_.max_lambda) break;
      }
    }
    if (diverged) break;
    if (!accepted) {
      // No step lowers chi^2 even with the largest damping: a minimum to working precision.
      report.converged = true;
      break;
    }
  }
  report.ok = true;
  report.chi_square = chi_square;
  return report;
}

// ---- incremental ----

SolveReport Smoother::FullRefactorization(SolveReport report,
                                          const std::vector<int>* relinearized_variables) {
  incremental_ready_ = false;
  marginal_factor_valid_ = false;
  // The factors to linearise: all of them at their variables' new linearisation points, or the
  // ones not yet in the system (BuildLayout marks every live factor as in it) and those of the
  // variables whose linearisation point moves.
  std::vector<char> linearize(factors_.size(), 1);
  if (relinearized_variables == nullptr) {
    RelinearizeAll();
  } else {
    for (size_t f = 0; f < factors_.size(); ++f) linearize[f] = !factors_[f].in_system;
    for (int v : *relinearized_variables) {
      Variable& variable = variables_[v];
      variable.linearization = Estimate(variable);
      variable.delta.setZero();
      for (int f : variable.factors) linearize[f] = 1;
    }
  }
  int live = 0;
  for (const Variable& v : variables_) live += v.alive ? 1 : 0;
  const int free_variables = std::max(options_.min_free_slots, live / 4);
  BuildLayout(free_variables * kPoseDim);
  const Layout& layout = *layout_;
  // The variables of the newest factors last (ISAM2's constrained ordering): the next
  // keyframes' factors are mostly on them.
  std::vector<char> recent;
  if (options_.ordering_recent_updates > 0) {
    recent.assign(layout.free_begin, 0);
    for (const Variable& v : variables_) {
      if (!v.alive || updates_ - v.newest_factor_update > options_.ordering_recent_updates) {
        continue;
      }
      for (int i = 0; i < v.dim; ++i) recent[v.offset + i] = 1;
    }
  }
  if (!cholesky_->Analyze(layout.n, layout.column_starts, layout.rows,
                          SparseCholesky::Form::kSimplicial, layout.n - layout.free_begin,
                          recent.empty() ? nullptr : &recent)) {
    report.error = "CHOLMOD could not analyse the normal equations";
    return report;
  }
  for (size_t f = 0; f < factors_.size(); ++f) {
    if (factors_[f].alive && linearize[f]) Linearize(&factors_[f]);
  }
  std::vector<double> values;
  AssembleNormalEquations(&values, &gradient_);
  if (!cholesky_->Factorize(values)) {
    report.error = "normal equations not positive definite (unconstrained problem?)";
    return report;
  }
  nonzeros_after_ordering_ = cholesky_->factor_nonzeros();
  factorization_work_ = cholesky_->FactorizationWork();
  // A re-ordering alone leaves (most) linearisation points where they were: the schedule of
  // full relinearisations counts on.
  if (relinearized_variables == nullptr) updates_since_refactorization_ = 0;
  needs_refactorization_ = false;
  incremental_ready_ = true;
  report.refactorized = true;
  for (const Variable& v : variables_) report.relinearized_variables += v.alive ? 1 : 0;
  return report;
}

std::vector<int> Smoother::VariablesToRelinearize() const {
  std::vector<int> moved;
  for (int v = 0; v < static_cast<int>(variables_.size()); ++v) {
    const Variable& variable = variables_[v];
    if (!variable.alive || !variable.in_system) continue;
    if (variable.delta.head(variable.dim).lpNorm<Eigen::Infinity>() >
        options_.relinearize_threshold) {
      moved.push_back(v);
    }
  }
  return moved;
}

Smoother::StepResult Smoother::SolveIncrementalStep(const std::vector<int>& moved) {
  std::vector<SparseCholesky::SparseColumn> updates;
  std::vector<SparseCholesky::SparseColumn> downdates;
  const auto subtract_gradient = [this](const Factor& f, double sign) {
    for (int k = 0; k < f.num_variables; ++k) {
      const Variable& v = variables_[f.variables[k]];
      gradient_.segment(v.offset, v.dim) +=
          sign * f.jacobian[k].topLeftCorner(f.rows, v.dim).transpose() * f.residual.head(f.rows);
    }
  };
  // Removed landmarks: an identity on their slot goes in (the matrix stays positive definite),
  // their factors come out; the slot is then decoupled with a zero gradient, so its step is 0.
  for (int index : removed_in_system_) {
    const Variable& landmark = variables_[index];
    for (int i = 0; i < landmark.dim; ++i) updates.push_back({{landmark.offset + i}, {1.0}});
    for (int f : landmark.factors) {
      Factor& factor = factors_[f];
      if (!factor.in_system) continue;
      AppendFactorColumns(factor, &downdates);
      subtract_gradient(factor, -1.0);
      factor.in_system = false;
    }
    gradient_.segment(landmark.offset, landmark.dim).setZero();
  }
  removed_in_system_.clear();
  // Variables whose pending step is large: their factors come out and go back relinearised.
  std::vector<int> relinearized_factors;
  for (int v : moved) {
    for (int f : variables_[v].factors) {
      if (factors_[f].alive && factors_[f].in_system) relinearized_factors.push_back(f);
    }
  }
  std::sort(relinearized_factors.begin(), relinearized_factors.end());
  relinearized_factors.erase(
      std::unique(relinearized_factors.begin(), relinearized_factors.end()),
      relinearized_factors.end());
  for (int f : relinearized_factors) {
    AppendFactorColumns(factors_[f], &downdates);
    subtract_gradient(factors_[f], -1.0);
  }
  for (int v : moved) {
    Variable& variable = variables_[v];
    variable.linearization = Estimate(variable);
    variable.delta.setZero();
  }
  for (int f : relinearized_factors) {
    Linearize(&factors_[f]);
    AppendFactorColumns(factors_[f], &updates);
    subtract_gradient(factors_[f], 1.0);
  }
  // New variables take the next free slots: their identity diagonal goes out.
  for (int v : pending_variables_) {
    Variable& variable = variables_[v];
    if (!variable.alive || variable.in_system) continue;
    variable.offset = next_free_offset_;
    next_free_offset_ += variable.dim;
    variable.in_system = true;
    for (int i = 0; i < variable.dim; ++i) {
      downdates.push_back({{variable.offset + i}, {1.0}});
    }
  }
  // New factors.
  for (int index : pending_factors_) {
    Factor& f = factors_[index];
    if (!f.alive || f.in_system) continue;
    f.in_system = true;
    Linearize(&f);
    AppendFactorColumns(f, &updates);
    subtract_gradient(f, 1.0);
  }
  pending_variables_.clear();
  pending_factors_.clear();
  // Rank updates dearer than a factorisation afresh (its work as at the last ordering, which a
  // re-ordering restores): the caller re-orders and re-factorises, from every factor (what was
  // changed above is rebuilt there).
  if (options_.max_update_work_share > 0.0 &&
      cholesky_->ModifyWork(updates) + cholesky_->ModifyWork(downdates) >
          options_.max_update_work_share * factorization_work_) {
    return StepResult::kTooDear;
  }
  // Updates first: the matrix stays positive definite through the downdates that follow.
  if (!cholesky_->Modify(true, updates) || !cholesky_->Modify(false, downdates)) {
    return StepResult::kFailed;
  }
  return StepResult::kDone;
}

SolveReport Smoother::Update() {
  SolveReport report;
  if (auto error = CheckAnchored()) {
    report.error = *error;
    return report;
  }
  report.iterations = 1;
  marginal_factor_valid_ = false;
  int pending_scalars = 0;
  for (int v : pending_variables_) {
    if (variables_[v].alive && !variables_[v].in_system) pending_scalars += variables_[v].dim;
  }
  const bool room = next_free_offset_ + pending_scalars <= layout_->n;
  const bool schedule = options_.full_relinearization_interval > 0 &&
                        updates_since_refactorization_ + 1 >=
                            options_.full_relinearization_interval;
  ++updates_;
  const bool relinearize =
      options_.relinearize_skip <= 1 || updates_ % options_.relinearize_skip == 0;
  bool incremental = incremental_ready_ && !needs_refactorization_ && room && !schedule;
  // What a refactorisation relinearises: everything (nullptr), or only these variables.
  std::vector<int> moved;
  const std::vector<int>* relinearized = nullptr;
  if (incremental && relinearize) {
    moved = VariablesToRelinearize();
    report.relinearized_variables = static_cast<int>(moved.size());
    if (report.relinearized_variables > options_.max_incremental_relinearizations) {
      // Too many for rank updates: they are relinearised, the rest stays, all re-factorised.
      incremental = false;
      relinearized = &moved;
    }
  }
  if (incremental) {
    const StepResult step = SolveIncrementalStep(moved);
    if (step != StepResult::kDone) incremental = false;  // numerical trouble: afresh
    // Too dear: the same linear system, re-ordered with the newest factors' variables last.
    moved.clear();
    if (step == StepResult::kTooDear) relinearized = &moved;
    ++updates_since_refactorization_;
  }
  if (!incremental) {
    report.relinearized_variables = 0;
    report = FullRefactorization(report, relinearized);
    if (!report.error.empty()) return report;
  }
  const Eigen::VectorXd step = cholesky_->Solve(-gradient_);
  if (step.size() != layout_->n || !step.allFinite()) {
    incremental_ready_ = false;
    report.error = "CHOLMOD solve failed";
    return report;
  }
  for (Variable& v : variables_) {
    if (v.alive && v.in_system) v.delta.head(v.dim) = step.segment(v.offset, v.dim);
  }
  // The fill (a pass over the factor's columns) is looked at with the relinearisation.
  if (relinearize &&
      cholesky_->factor_nonzeros() > options_.reorder_fill_ratio * nonzeros_after_ordering_) {
    needs_refactorization_ = true;
  }
  marginal_factor_valid_ = true;
  report.ok = true;
  report.chi_square =
      options_.update_chi_square ? ChiSquare() : std::numeric_limits<double>::quiet_NaN();
  return report;
}

// ---- results ----

std::optional<Eigen::Vector3d> Smoother::PoseEstimate(PoseId id) const {
  const auto index = Find(pose_index_, id);
  if (!index) return std::nullopt;
  return Estimate(variables_[*index]);
}

std::optional<Eigen::Vector2d> Smoother::LandmarkEstimate(LandmarkId id) const {
  const auto index = Find(landmark_index_, id);
  if (!index) return std::nullopt;
  return Estimate(variables_[*index]).head<2>();
}

std::vector<PoseId> Smoother::PoseIds() const {
  std::vector<PoseId> ids;
  for (const Variable& v : variables_) {
    if (v.is_pose && v.alive) ids.push_back(v.id);
  }
  return ids;
}

std::vector<LandmarkId> Smoother::LandmarkIds() const {
  std::vector<LandmarkId> ids;
  for (const Variable& v : variables_) {
    if (!v.is_pose && v.alive) ids.push_back(v.id);
  }
  return ids;
}

bool Smoother::EnsureMarginalFactor() {
  if (marginal_factor_valid_ && cholesky_->factorized()) return true;
  if (CheckAnchored()) return false;
  // The batch factor (damped, at the previous iterate) or none: factorise J^T J at the
  // current estimate. The incremental factor is rebuilt at the next Update.
  incremental_ready_ = false;
  RelinearizeAll();
  BuildLayout(0);
  const Layout& layout = *layout_;
  if (!cholesky_->Analyze(layout.n, layout.column_starts, layout.rows,
                          SparseCholesky::Form::kSupernodal)) {
    return false;
  }
  for (Factor& f : factors_) {
    if (f.alive) Linearize(&f);
  }
  std::vector<double> values;
  Eigen::VectorXd gradient;
  AssembleNormalEquations(&values, &gradient);
  if (!cholesky_->Factorize(values)) return false;
  marginal_factor_valid_ = true;
  return true;
}

std::optional<Eigen::MatrixXd> Smoother::MarginalBlocks(const std::vector<int>& variables) {
  if (!EnsureMarginalFactor()) return std::nullopt;
  int columns = 0;
  for (int v : variables) columns += variables_[v].dim;
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(layout_->n, columns);
  int column = 0;
  for (int v : variables) {
    for (int i = 0; i < variables_[v].dim; ++i) unit(variables_[v].offset + i, column++) = 1.0;
  }
  const Eigen::MatrixXd solved = cholesky_->SolveColumns(unit);
  if (solved.size() == 0 || !solved.allFinite()) return std::nullopt;
  Eigen::MatrixXd blocks(3, columns);
  blocks.setZero();
  column = 0;
  for (int v : variables) {
    const int dim = variables_[v].dim;
    blocks.block(0, column, dim, dim) = solved.block(variables_[v].offset, column, dim, dim);
    column += dim;
  }
  return blocks;
}

std::optional<Eigen::Matrix3d> Smoother::PoseCovariance(PoseId id) {
  const auto index = Find(pose_index_, id);
  if (!index) return std::nullopt;
  const auto blocks = MarginalBlocks({*index});
  if (!blocks) return std::nullopt;
  if (options_.pose_update == SmootherOptions::PoseUpdate::kExponential) {
    // The block is in the pose's own frame (the chart of the steps): back to (x, y, theta).
    const Eigen::Matrix3d g = RetractionJacobianAtZero(variables_[*index].linearization(2));
    return Eigen::Matrix3d(g * *blocks * g.transpose());
  }
  return Eigen::Matrix3d(*blocks);
}

std::optional<Eigen::Matrix2d> Smoother::LandmarkCovariance(LandmarkId id) {
  return LandmarkCovariances({id}).front();
}

std::vector<std::optional<Eigen::Matrix2d>> Smoother::LandmarkCovariances(
    const std::vector<LandmarkId>& ids) {
  std::vector<std::optional<Eigen::Matrix2d>> result(ids.size());
  constexpr size_t kColumnsPerSolve = 32;  // landmarks solved together
  std::vector<int> chunk;
  std::vector<size_t> where;
  const auto flush = [&]() {
    if (chunk.empty()) return;
    const auto blocks = MarginalBlocks(chunk);
    if (blocks) {
      for (size_t k = 0; k < chunk.size(); ++k) {
        result[where[k]] = Eigen::Matrix2d(blocks->block(0, 2 * k, 2, 2));
      }
    }
    chunk.clear();
    where.clear();
  };
  for (size_t k = 0; k < ids.size(); ++k) {
    const auto index = Find(landmark_index_, ids[k]);
    if (!index) continue;
    chunk.push_back(*index);
    where.push_back(k);
    if (chunk.size() == kColumnsPerSolve) flush();
  }
  flush();
  return result;
}

int Smoother::num_poses() const { return static_cast<int>(pose_index_.size()); }
int Smoother::num_landmarks() const { return static_cast<int>(landmark_index_.size()); }
int Smoother::num_factors() const {
  return static_cast<int>(
      std::count_if(factors_.begin(), factors_.end(), [](const Factor& f) { return f.alive; }));
}
double Smoother::factor_nonzeros() const { return cholesky_->factor_nonzeros(); }

}  // namespace slammtt
