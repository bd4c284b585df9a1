// Sparse nonlinear least squares over SE(2) keyframe poses and static point landmarks: the
// project's smoother (docs/smoother.md). Pure: Eigen and CHOLMOD, no LCM, no files, no clocks.
//
// The problem: minimise chi^2 = sum over factors of r^T Lambda r (r a factor's residual,
// Lambda its information matrix; factors.h gives each residual) over the poses
// (x, y, theta; m, m, rad; map frame) and landmarks (x, y; m). Factors:
// - odometry between two poses (relative pose, 3x3 information),
// - range-bearing of a landmark from a pose through a laser at a mount offset (paper eqs.
//   10-11, 2x2 information in (range, bearing)),
// - relative position of a landmark in a pose's frame (2x2 information),
// - priors on a pose (3x3) or a landmark (2x2).
// Every connected part of the factor graph needs a prior: without one its position and heading
// are free (every other factor is unchanged by moving the whole part), and Optimize / Update
// say so instead of solving.
//
// Two ways to solve, on the same variables and factors:
// - Optimize (batch): Gauss-Newton or Levenberg-Marquardt from the current estimate to
//   convergence, every factor relinearised at every iteration, the normal equations
//   J^T J dx = -J^T r (whitened) factorised by CHOLMOD supernodal Cholesky with its own
//   fill-reducing ordering, the symbolic analysis reused while the pattern stays the same.
// - Update (incremental, one call per keyframe, after adding that keyframe's variables and
//   factors): one Gauss-Newton step, as ISAM2 takes (Kaess et al., IJRR 31(2), 2012). Each
//   variable keeps a linearisation point; only variables whose pending step exceeds
//   relinearize_threshold move it, and only their factors are relinearised. The factor of the
//   normal equations is kept between calls and modified by rank-k updates and downdates
//   (new factors, relinearised factors, new variables in slots reserved at the end of the
//   ordering), so a keyframe that touches only recent variables costs little. Every
//   full_relinearization_interval updates, when the factor's fill has grown by
//   reorder_fill_ratio, when the slots run out or after an estimate is set, everything is
//   relinearised, re-ordered and re-factorised (simplicial LDL^T, which updates need). When
//   more than max_incremental_relinearizations variables must be relinearised at once, or when
//   the rank updates would cost more than max_update_work_share of a factorisation, only the
//   variables due are relinearised and the whole is re-ordered and re-factorised. A
//   removed landmark's factors leave the kept factor by rank downdates (its slot stays, an
//   isolated identity, until then).
// The chi-square at the returned estimate is in every SolveReport.
//
// Bad input is refused with a one-line reason and changes nothing: non-finite numbers, an
// information matrix that is not symmetric positive definite, a factor naming an unknown
// variable, an id used twice, an unconstrained problem, a solve that cannot factorise.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/options_schema.h"
#include "estimator/range_bearing_model.h"
#include "smoother/sparse_cholesky.h"

namespace slammtt {

using PoseId = int64_t;
using LandmarkId = int64_t;

struct SmootherOptions {
  enum class Method { kGaussNewton, kLevenbergMarquardt };
  enum class Damping {
    kIdentity,  // LM adds lambda I (GTSAM's LevenbergMarquardtParams default)
    kDiagonal,  // LM adds lambda diag(J^T J) (Marquardt's scaling)
  };
  // How a step moves a pose: adding to (x, y, theta), or pose * exp(step), the step in the
  // pose's own frame as GTSAM's Pose2 retraction takes it. Both reach the same optima; from far
  // away (Victoria Park from its odometry chain) LM's path, and so the local minimum it ends in,
  // depends on the chart its damping acts in (docs/smoother.md, "Victoria Park").
  enum class PoseUpdate { kAdditive, kExponential };
  PoseUpdate pose_update = PoseUpdate::kAdditive;
  // Batch (Optimize).
  Method method = Method::kLevenbergMarquardt;
  Damping damping = Damping::kIdentity;
  int max_iterations = 500;
  // Converged when an accepted step lowers chi^2 by less than this fraction of it...
  double relative_tolerance = 1e-10;
  // ... or by less than this much (chi^2 units).
  double absolute_tolerance = 0.0;
  // Levenberg-Marquardt as GTSAM's LevenbergMarquardtOptimizer runs it with its default
  // LevenbergMarquardtParams (gtsam/nonlinear/LevenbergMarquardtOptimizer.cpp): a step is
  // accepted when the actual decrease of chi^2 is more than min_model_fidelity times the
  // decrease the linearised model predicts; lambda is then divided by lambda_factor, else
  // multiplied by it; LM stops when lambda would exceed max_lambda.
  double initial_lambda = 1e-5;      // lambdaInitial
  double lambda_factor = 10.0;       // lambdaFactor
  double max_lambda = 1e5;           // lambdaUpperBound
  double min_model_fidelity = 1e-3;  // minModelFidelity

  // Incremental (Update).
  double relinearize_threshold = 0.1;  // |step| of any component (m or rad); ISAM2's default
  int relinearize_skip = 10;  // relinearisation is considered every this many updates (ISAM2)
  // More variables to relinearise than this at once: relinearise, re-order and re-factorise
  // everything instead (one factorisation costs less than that many rank updates).
  int max_incremental_relinearizations = 16;
  int full_relinearization_interval = 200;  // updates between full relinearisations (0: never)
  double reorder_fill_ratio = 2.0;  // refactor when the factor's nonzeros grow this much
  // An update whose rank updates would cost more than this share of a factorisation afresh
  // (both counted from the factor's structure: SparseCholesky::ModifyWork, FactorizationWork)
  // re-orders and re-factorises instead. After a loop closes, factors on landmarks mapped long
  // ago, eliminated early, run along the whole height of the elimination tree; re-ordered, those
  // landmarks come last and the next keyframes' updates are short again. 0: never.
  double max_update_work_share = 0.25;
  int min_free_slots = 64;          // variables' room reserved at the end of the ordering
  // A refactorisation orders the variables of the factors added in this many last updates
  // after the others (constrained minimum degree, CAMD; ISAM2 orders its newest factors' keys
  // last the same way): the next keyframes observe mostly the same variables, and their rank
  // updates then run along short paths of the elimination tree. 0: CHOLMOD's own ordering.
  int ordering_recent_updates = 1;
  // Update reports chi^2 at the returned estimate: a pass over every factor, as costly as the
  // rest of a small update. false: Update's chi_square is NaN (ChiSquare() on request), as
  // ISAM2's update() evaluates no error unless asked (ISAM2Params::evaluateNonlinearError).
  bool update_chi_square = true;
};

// The schema of SmootherOptions (common/options_schema.h): every field with its range and one
// line of documentation (docs/smoother.md, "Options").
void VisitSmootherOptions(OptionVisitor* visitor, SmootherOptions* options);

// "" when the options are usable, else one line naming the first problem: a value outside its
// range (VisitSmootherOptions), or max_lambda < initial_lambda. (A lambda_factor of at most 1 or
// an initial_lambda of 0 would let Levenberg-Marquardt reject steps for ever.)
std::string CheckSmootherOptions(const SmootherOptions& options);

struct SolveReport {
  bool ok = false;
  std::string error;                // one line when !ok
  // Sum of squared whitened residuals at the estimate (NaN from an Update with
  // update_chi_square false).
  double chi_square = 0.0;
  double initial_chi_square = 0.0;  // batch: the same before the solve (incremental: 0)
  int iterations = 0;               // batch: accepted + rejected LM steps; incremental: 1
  // Batch: a tolerance was met, or no step with lambda up to max_lambda lowers chi^2 (where
  // GTSAM's LM stops too); false when max_iterations ran out or Gauss-Newton made chi^2 worse.
  bool converged = false;
  int relinearized_variables = 0;   // incremental: variables whose linearisation point moved
  bool refactorized = false;        // incremental: this update re-ordered and re-factorised
};

class Smoother {
 public:
  // Throws std::invalid_argument with CheckSmootherOptions()'s message for unusable options.
  explicit Smoother(const SmootherOptions& options = {});
  ~Smoother();
  Smoother(const Smoother&) = delete;
  Smoother& operator=(const Smoother&) = delete;

  // Variables, with their initial estimates. Error: id in use, non-finite value.
  std::optional<std::string> AddPose(PoseId id, const Eigen::Vector3d& initial_pose);
  std::optional<std::string> AddLandmark(LandmarkId id, const Eigen::Vector2d& initial_position);
  // The landmark and every factor on it leave the problem (it turned out to move). Error:
  // unknown id.
  std::optional<std::string> RemoveLandmark(LandmarkId id);

  // Factors (see factors.h for each residual). Error: unknown variable, non-finite value,
  // information not symmetric positive definite, a pose related to itself.
  std::optional<std::string> AddOdometry(PoseId from, PoseId to, const Eigen::Vector3d& relative,
                                         const Eigen::Matrix3d& information);
  std::optional<std::string> AddRangeBearing(PoseId pose, LandmarkId landmark,
                                             const Eigen::Vector2d& range_bearing,
                                             const Eigen::Matrix2d& information,
                                             const SensorMount& mount = {});
  std::optional<std::string> AddRelativePosition(PoseId pose, LandmarkId landmark,
                                                 const Eigen::Vector2d& position_in_pose,
                                                 const Eigen::Matrix2d& information);
  std::optional<std::string> AddPosePrior(PoseId pose, const Eigen::Vector3d& prior,
                                          const Eigen::Matrix3d& information);
  std::optional<std::string> AddPointPrior(LandmarkId landmark, const Eigen::Vector2d& prior,
                                           const Eigen::Matrix2d& information);

  // Replace a variable's estimate (a solution from elsewhere, a correction): the next Update
  // re-factorises. Error: unknown id, non-finite value.
  std::optional<std::string> SetPoseEstimate(PoseId id, const Eigen::Vector3d& pose);
  std::optional<std::string> SetLandmarkEstimate(LandmarkId id, const Eigen::Vector2d& position);

  // Batch: iterate to convergence from the current estimate (see the header comment).
  SolveReport Optimize();
  // Incremental: one step after a keyframe's variables and factors were added.
  SolveReport Update();

  // Current estimates; nullopt for an unknown id.
  std::optional<Eigen::Vector3d> PoseEstimate(PoseId id) const;
  std::optional<Eigen::Vector2d> LandmarkEstimate(LandmarkId id) const;
  std::vector<PoseId> PoseIds() const;          // in the order added
  std::vector<LandmarkId> LandmarkIds() const;  // in the order added, removed ones left out

  // Marginal covariances at the current estimate, in (x, y, theta) / (x, y) of the map frame,
  // from the factor of the normal equations (solves with unit vectors, sparse_cholesky.h).
  // nullopt for an unknown id or when the system cannot be factorised.
  std::optional<Eigen::Matrix3d> PoseCovariance(PoseId id);
  std::optional<Eigen::Matrix2d> LandmarkCovariance(LandmarkId id);
  // Several landmarks at once (columns solved together); nullopt entries for unknown ids.
  std::vector<std::optional<Eigen::Matrix2d>> LandmarkCovariances(
      const std::vector<LandmarkId>& ids);

  // Sum of squared whitened residuals of every factor at the current estimate.
  double ChiSquare() const;
  int num_poses() const;
  int num_landmarks() const;
  int num_factors() const;
  // Nonzeros of the factor kept for Update (0 before the first one): a fill measure.
  double factor_nonzeros() const;

 private:
  struct Variable;
  struct Factor;
  struct Layout;

  std::optional<std::string> AddVariable(bool is_pose, int64_t id, const Eigen::Vector3d& value);
  std::optional<std::string> AddFactor(Factor factor);
  // Every live variable's part of the graph has a prior (else the error naming one that has
  // not). Kept as factors arrive, so that each Update need not pass over the whole graph.
  std::optional<std::string> CheckAnchored();
  int ComponentRoot(int variable);
  void JoinComponents(const Factor& factor);
  void RebuildComponents();
  Eigen::Vector3d Estimate(const Variable& variable) const;
  double FactorChiSquare(const Factor& factor, bool at_linearization_point) const;
  void Linearize(Factor* factor) const;
  void RelinearizeAll();
  void BuildLayout(int free_slots);
  void AssembleNormalEquations(std::vector<double>* values, Eigen::VectorXd* gradient) const;
  void AppendFactorColumns(const Factor& factor,
                           std::vector<SparseCholesky::SparseColumn>* columns) const;
  // Re-orders and re-factorises the whole system. Without relinearized_variables every
  // variable's linearisation point moves to its estimate first; with them only theirs does, and
  // only their factors and those not yet in the system are linearised (none given: a
  // re-ordering, the linear system stays the same).
  SolveReport FullRefactorization(SolveReport report,
                                  const std::vector<int>* relinearized_variables);
  enum class StepResult { kDone, kTooDear, kFailed };
  // One update by rank updates; `moved`: the variables whose linearisation point moves now.
  StepResult SolveIncrementalStep(const std::vector<int>& moved);
  std::vector<int> VariablesToRelinearize() const;
  double LinearizedChiSquare() const;
  bool EnsureMarginalFactor();
  std::optional<Eigen::MatrixXd> MarginalBlocks(const std::vector<int>& variables);

  SmootherOptions options_;
  std::vector<Variable> variables_;
  std::vector<Factor> factors_;
  std::unordered_map<PoseId, int> pose_index_;
  std::unordered_map<LandmarkId, int> landmark_index_;
  std::unique_ptr<Layout> layout_;
  std::unique_ptr<SparseCholesky> cholesky_;
  // Incremental state: the factor holds J^T J at the linearisation points, gradient_ its J^T r.
  bool incremental_ready_ = false;
  bool needs_refactorization_ = false;
  int updates_since_refactorization_ = 0;
  double factorization_work_ = 0.0;  // SparseCholesky::FactorizationWork at the last ordering
  int updates_ = 0;
  // Added since the last update, not yet in the kept factor (indices).
  std::vector<int> pending_variables_;
  std::vector<int> pending_factors_;
  // Landmarks removed since the last update that are in the kept factor (indices).
  std::vector<int> removed_in_system_;
  double nonzeros_after_ordering_ = 0.0;
  Eigen::VectorXd gradient_;
  int next_free_offset_ = 0;
  // The factor in cholesky_ is of the undamped normal equations at the current linearisation.
  bool marginal_factor_valid_ = false;
  // Connected parts of the factor graph (union-find over variable indices) and whether each
  // root's part has a prior, updated as variables and factors arrive; a removal makes them
  // stale and the next CheckAnchored rebuilds them.
  std::vector<int> component_parent_;
  std::vector<char> component_anchored_;
  int unanchored_components_ = 0;
  int live_variables_ = 0;
  bool components_stale_ = false;
};

}  // namespace slammtt
