// The one EKF state of the estimator (paper eq. 2): robot pose, static landmarks and moving
// objects, with a dense covariance and block access.
//
// Layout of the state vector: the robot block at indices 0-3, the pose (x, y, heading) at 0-2
// and the odometry's systematic heading drift b [rad per metre travelled] at 3 (the paper's
// robot state augmented with an odometry calibration parameter, as in simultaneous
// localisation and odometry self-calibration: Martinelli, Tomatis and Siegwart, Autonomous
// Robots 22, 2007; ekf_prediction.h), then every object in slots. An object always has a
// position slot (x, y); an object that carries velocity states (a moving or undecided object,
// paper eq. 5) also has a velocity slot (vx, vy). The
// two slots of one object need not be adjacent: a landmark that starts to move gets its
// velocity slot appended at the end, and removing states compacts the vector, so objects refer
// to their slots by index. A static landmark (eq. 4) has no velocity slot. An object with
// velocity states may also have an anchor slot (x, y): a stochastic clone of its position taken
// when it got them (AddStationaryAnchor), its stationary hypothesis.
// Line landmarks (walls, furniture sides: line_model.h) have a slot of two states (rho, alpha)
// each, in the same vector and covariance; they are never objects (a line never moves, is
// never tracked nor classified) and only line_landmarks.h reads and writes them.
//
// The covariance is stored symmetric (both triangles valid) in a matrix with spare capacity so
// that adding objects does not reallocate every time. Every operation keeps it symmetric; the
// update routines (ekf_update.h) keep it positive semi-definite.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace slammtt {

// Same numbering as track_t's CLASS_* constants.
enum class ObjectClass : int8_t { kStatic = 0, kMoving = 1, kUndecided = 2 };
// What an object is (people.h); same numbering as track_t's KIND_* constants.
enum class ObjectKind : int8_t { kOther = 0, kPerson = 1 };

// Book-keeping of one object (track management and classification read and write it).
struct ObjectRecord {
  int64_t id = 0;
  ObjectClass object_class = ObjectClass::kUndecided;
  bool confirmed = false;
  int hits = 0;                    // scans in which a measurement updated the object
  // Of those, the scans whose measurement was a person feature, and the kind they make it
  // (people.h: a person when most of its measurements were person features).
  int person_hits = 0;
  ObjectKind kind = ObjectKind::kOther;
  // Of the person features, those of two legs paired (people.h, report_min_pair_hits).
  int pair_hits = 0;
  // The person feature that started the object: its two legs' confidence (0: one leg, or not
  // a person feature; people.h, ReportedAtBirth).
  double birth_pair_confidence = 0.0;
  // The object's last scans, newest in bit 0: 1 for a scan with a measurement (M-of-N
  // confirmation, TrackManagementOptions::confirm_window_scans).
  uint32_t recent_hits = 0;
  // The same scans, 1 for every scan of its life (hit or miss): a young object's misses are
  // counted over the scans it lived (TrackManagementOptions::report_other_hits).
  uint32_t recent_scans = 0;
  // The same scans, 1 for a scan without a measurement in which it should have been seen
  // (track_management.h, ExpectedVisible).
  uint32_t recent_visible_misses = 0;
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;
  Eigen::Vector2d last_seen_m = Eigen::Vector2d::Zero();  // position estimate after that scan
  int64_t last_update_utime = 0;   // last scan whose measurement updated the state
  double unseen_in_view_s = 0.0;   // time it should have been seen without a measurement
  double unseen_observable_s = 0.0;  // time without a measurement inside the sensor's geometry
  // Classification evidence (motion_classifier.h).
  int moving_evidence_scans = 0;   // consecutive scans whose velocity says "moving"
  // Scans with a measurement since the object got its velocity states, that scan included
  // (MotionClassifierOptions::moving_evidence_min_hits).
  int hits_with_velocity = 0;
  // Where the object's estimate was when the current "still" window opened (at creation, when
  // it gained velocity states and at every scan of moving evidence).
  Eigen::Vector2d still_anchor_m = Eigen::Vector2d::Zero();
  int64_t still_anchor_utime = 0;
  double still_anchor_variance_m2 = 0.0;  // largest eigenvalue of its position covariance then
  // Static landmark: its last measurements' offsets from it in the map frame (measured point
  // minus estimate) with their covariances, a ring of kOffsetWindow (motion_classifier.h).
  static constexpr int kOffsetWindow = 4;
  std::array<Eigen::Vector2d, kOffsetWindow> offsets_m;
  std::array<Eigen::Matrix2d, kOffsetWindow> offset_covariances;
  int num_offsets = 0;             // valid entries (at most kOffsetWindow)
  int next_offset = 0;             // where the next one goes
  int64_t class_change_utime = 0;  // last change of object_class
  // A tentative object that may be a lost mover seen again: that track's id (0: none;
  // track_management.h, ChooseReacquisitions).
  int64_t continues_id = 0;
  // A landmark that re-entered the state from the local window's archive and has had no
  // measurement since (landmark_window.h: HoldBackUnsureReentries).
  bool reentered_unseen = false;
};

// Book-keeping of one line landmark (line_landmarks.h).
struct LineRecord {
  int64_t id = 0;                  // from the same counter as the objects' ids
  int hits = 0;                    // scans in which a line feature was associated with it
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;     // last scan with an associated line feature
  int64_t last_update_utime = 0;   // last scan whose line feature updated the state
  // The observed extent: the union of the associated features' extents, as coordinates along
  // the line's direction (-sin alpha, cos alpha) [m], from <= to (line_model.h:
  // PositionAlongLine). For association (overlap) and pictures; not part of the state.
  double extent_from_m = 0.0;
  double extent_to_m = 0.0;
};

struct StateLine {
  int param_index = -1;  // rho at param_index, alpha at param_index + 1
  LineRecord record;
};

struct StateObject {
  int position_index = -1;  // x at position_index, y at position_index + 1
  int velocity_index = -1;  // vx, vy; -1 for a static landmark
  // The stationary hypothesis of an object with velocity states: a copy of its position taken
  // when it got them (AddStationaryAnchor), -1 for none. No model moves it and no measurement
  // updates it directly; it keeps, through its correlations, where the object was then.
  int anchor_index = -1;
  // First-estimate Jacobians (SlamState::first_estimate_jacobians): where the object was when it
  // entered the state, or when it became a static landmark (lost its velocity states). A static
  // landmark's measurement Jacobians are evaluated here, not at its current estimate.
  Eigen::Vector2d first_estimate_m = Eigen::Vector2d::Zero();
  ObjectRecord record;
  bool has_velocity() const { return velocity_index >= 0; }
  bool has_anchor() const { return anchor_index >= 0; }
};

class SlamState {
 public:
  static constexpr int kRobotPoseDim = 3;     // x, y, heading
  static constexpr int kHeadingDriftIndex = 3;  // b [rad/m]
  static constexpr int kRobotDim = 4;         // pose + b; the first object starts here

  // A state with only the robot, at `pose` with covariance `pose_covariance`, and a heading
  // drift of mean 0 and variance `heading_drift_variance` [rad^2/m^2], independent of the pose
  // (0: the drift is known to be zero and stays so unless a prediction adds noise to it).
  SlamState(const Eigen::Vector3d& pose, const Eigen::Matrix3d& pose_covariance,
            double heading_drift_variance = 0.0);

  int dim() const { return dim_; }
  int num_objects() const { return static_cast<int>(objects_.size()); }

  // Views of the active part of the mean and covariance (valid until the dimension changes).
  // Taking a mutable view counts as a change (revision()).
  Eigen::VectorBlock<Eigen::VectorXd> mean() {
    ++revision_;
    return mean_.head(dim_);
  }
  Eigen::VectorBlock<const Eigen::VectorXd> mean() const { return mean_.head(dim_); }
  Eigen::Block<Eigen::MatrixXd> covariance() {
    ++revision_;
    return cov_.topLeftCorner(dim_, dim_);
  }
  Eigen::Block<const Eigen::MatrixXd> covariance() const {
    return cov_.topLeftCorner(dim_, dim_);
  }

  Eigen::Vector3d robot_pose() const { return mean_.head<3>(); }

  // First-estimate Jacobians (Huang, Mourikis and Roumeliotis, "Analysis and improvement of the
  // consistency of extended Kalman filter based SLAM", ICRA 2008): an EKF whose Jacobians are
  // evaluated at estimates that later updates moved gains information on the absolute heading,
  // which no sensor of a robot seeing only its own landmarks gives (docs/estimator.md, "First-
  // estimate Jacobians"). With this on, the prediction's Jacobian uses the pose predicted at the
  // previous scan (not the updated one) and a static landmark's measurement Jacobians use the
  // pose predicted for this scan and its first estimate (StateObject::first_estimate_m); the
  // innovations still use the current estimates. Objects with velocity states keep the
  // standard Jacobians. Off: the standard EKF.
  bool first_estimate_jacobians() const { return first_estimate_jacobians_; }
  void set_first_estimate_jacobians(bool on) { first_estimate_jacobians_ = on; }
  // The robot's pose as predicted for the current scan (before its updates), once a
  // prediction has set it (ApplyRobotPrediction).
  bool has_predicted_pose() const { return has_predicted_pose_; }
  const Eigen::Vector3d& predicted_pose() const { return predicted_pose_; }
  void set_predicted_pose(const Eigen::Vector3d& pose) {
    predicted_pose_ = pose;
    has_predicted_pose_ = true;
  }
  Eigen::Matrix3d robot_covariance() const { return cov_.topLeftCorner<3, 3>(); }
  // The odometry's heading drift b [rad per metre travelled] and its variance.
  double heading_drift_rad_per_m() const { return mean_(kHeadingDriftIndex); }
  double heading_drift_variance() const { return cov_(kHeadingDriftIndex, kHeadingDriftIndex); }

  // A number that changes whenever the mean, the covariance or the layout of the state may have
  // changed: every mutating call and every mutable view of the mean or the covariance counts
  // (a view written after a later read of revision() is not seen: read it after the writes).
  // Records (object(k).record) are book-keeping and do not count. What is computed from the
  // state alone (the predicted observations, observation_predictions.h) can be reused while
  // the revision stays the same. A copy of the state carries the revision of its original.
  uint64_t revision() const { return revision_; }

  const std::vector<StateObject>& objects() const { return objects_; }
  // For the record only: the slot indices belong to the state.
  StateObject& object(int k) { return objects_[static_cast<size_t>(k)]; }
  const StateObject& object(int k) const { return objects_[static_cast<size_t>(k)]; }

  Eigen::Vector2d position(int k) const { return mean_.segment<2>(object(k).position_index); }
  // Zero for a static landmark.
  Eigen::Vector2d velocity(int k) const;
  // 4x4 over (x, y, vx, vy); the velocity rows and columns are zero for a static landmark.
  Eigen::Matrix4d ObjectCovariance(int k) const;

  // Adds an object whose position error is G (robot pose error; a point seen from the robot
  // does not depend on the heading drift, so G is 2x3 over the pose) plus an independent error of
  // covariance `independent_covariance` (e.g. a point seen from the robot: G = d point / d
  // robot, independent = J_z R J_z^T). So P_pp = G P_rr G^T + C and P_p,x = G P_r,x for every
  // other state x. Returns the new object's index.
  int AddObject(const Eigen::Vector2d& position, const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                const Eigen::Matrix2d& independent_covariance, const ObjectRecord& record);

  // Adds a line landmark (rho, alpha) (line_model.h) whose error is G (robot pose error) plus an
  // independent error of covariance `independent_covariance`, as AddObject does for a point.
  // Returns the new line's index.
  int AddLine(const Eigen::Vector2d& line, const Eigen::Matrix<double, 2, 3>& jacobian_robot,
              const Eigen::Matrix2d& independent_covariance, const LineRecord& record);

  int num_lines() const { return static_cast<int>(lines_.size()); }
  const std::vector<StateLine>& lines() const { return lines_; }
  // For the record only: the slot index belongs to the state.
  StateLine& line(int k) { return lines_[static_cast<size_t>(k)]; }
  const StateLine& line(int k) const { return lines_[static_cast<size_t>(k)]; }
  Eigen::Vector2d line_params(int k) const { return mean_.segment<2>(line(k).param_index); }
  Eigen::Matrix2d LineCovariance(int k) const {
    const int p = line(k).param_index;
    return cov_.block<2, 2>(p, p);
  }

  // Starts object k again, keeping its slot and record: its position becomes `position` with
  // the covariance and cross-covariances AddObject gives a new object (G = jacobian_robot,
  // independent error `independent_covariance`), its velocity states (if any) zero with
  // covariance `velocity_covariance` and independent of everything, its stationary anchor (if
  // any) a fresh copy of the new position. What the state knew of the object is forgotten, not
  // what its measurements told about the robot.
  void RestartObject(int k, const Eigen::Vector2d& position,
                     const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                     const Eigen::Matrix2d& independent_covariance,
                     const Eigen::Matrix2d& velocity_covariance);

  // Gives object k velocity states with the given mean and a covariance independent of
  // everything else (the prior of a landmark that starts to move). No-op if it has them.
  void AddVelocity(int k, const Eigen::Vector2d& velocity, const Eigen::Matrix2d& covariance);

  // Makes object k static: conditions the whole state on its velocity being exactly zero (a
  // perfect pseudo-measurement v = 0), then removes the velocity states (marginalisation,
  // which for a Gaussian is dropping rows and columns). No-op without velocity states.
  void RemoveVelocityAssumingZero(int k);

  // Stochastic cloning (Roumeliotis and Burdick, "Stochastic cloning: a generalized framework
  // for processing relative state measurements", ICRA 2002): appends a copy of object k's
  // position (same mean, the position's rows and columns of P, perfectly correlated with it),
  // the object's stationary anchor. No-op if it has one.
  void AddStationaryAnchor(int k);

  // The object did not move since its anchor was taken: conditions the whole state on
  // position = anchor (a perfect pseudo-measurement of the displacement, 2 dof), when the
  // displacement's NIS d^T S^-1 d is below `gate_chi2`; then removes the anchor states
  // (marginalisation). Returns whether it conditioned. No-op (false) without an anchor.
  bool ConditionOnAnchorAndRemoveIt(int k, double gate_chi2);

  // Removes object k's anchor states (marginalisation: the hypothesis is given up). No-op
  // without one.
  void RemoveAnchor(int k);

  // Removes the listed objects (indices into objects(), any order, duplicates ignored) and
  // their states; the other objects keep their order.
  void RemoveObjects(std::vector<int> object_indices);

  // P <- P - V V^T with V = v_transposed^T (dim x m): the covariance downdate of an update in
  // factored form (ekf_update.h). Only the lower triangle is computed, then mirrored, so P
  // stays exactly symmetric.
  void SubtractSymmetricProduct(const Eigen::MatrixXd& v_transposed);

  // Copies the lower triangle onto the upper one.
  void MirrorLowerTriangle();
  // Copies row i onto column i (after a transform computed the row: keeps P exactly symmetric).
  void MirrorRowToColumn(int i) {
    ++revision_;
    cov_.col(i).head(dim_) = cov_.row(i).head(dim_).transpose();
  }

 private:
  bool first_estimate_jacobians_ = false;
  bool has_predicted_pose_ = false;
  Eigen::Vector3d predicted_pose_ = Eigen::Vector3d::Zero();
  void Reserve(int dim);
  int AppendStates(int count);  // uninitialised mean/covariance rows; returns first index
  // Appends two states of mean `value` and error G (pose) + independent (AddObject, AddLine).
  int AppendCorrelatedPair(const Eigen::Vector2d& value,
                           const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                           const Eigen::Matrix2d& independent_covariance);
  // Sets states p, p + 1 to `value` with that error against the first `columns` states, their
  // own covariance included (AppendCorrelatedPair, RestartObject).
  void SetCorrelatedPair(int p, const Eigen::Vector2d& value,
                         const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                         const Eigen::Matrix2d& independent_covariance, int columns);
  void RemoveStates(const std::vector<int>& sorted_state_indices);

  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_;  // capacity x capacity; the top-left dim_ x dim_ block is the state's
  int dim_ = 0;
  std::vector<StateObject> objects_;
  std::vector<StateLine> lines_;
  uint64_t revision_ = 0;
};

}  // namespace slammtt
