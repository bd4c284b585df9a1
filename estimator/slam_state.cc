#include "estimator/slam_state.h"

#include <Eigen/Cholesky>
#include <algorithm>

namespace slammtt {

SlamState::SlamState(const Eigen::Vector3d& pose, const Eigen::Matrix3d& pose_covariance,
                     double heading_drift_variance) {
  Reserve(64);
  dim_ = kRobotDim;
  mean_.head<3>() = pose;
  mean_(kHeadingDriftIndex) = 0.0;
  cov_.topLeftCorner<kRobotDim, kRobotDim>().setZero();
  cov_.topLeftCorner<3, 3>() = 0.5 * (pose_covariance + pose_covariance.transpose());
  cov_(kHeadingDriftIndex, kHeadingDriftIndex) = heading_drift_variance;
}

void SlamState::Reserve(int dim) {
  const Eigen::Index capacity = cov_.rows();
  if (dim <= capacity) return;
  Eigen::Index new_capacity = std::max<Eigen::Index>(dim, 2 * capacity);
  // Column stride of a multiple of 4 KiB would map every element of a row to the same cache
  // set (row reads of a 1024 x 1024 matrix then miss on every access): round up to whole cache
  // lines and keep the stride an odd number of cache lines.
  constexpr Eigen::Index kLine = 8;  // doubles per 64-byte cache line
  new_capacity = (new_capacity + kLine - 1) / kLine;
  if (new_capacity % 2 == 0) ++new_capacity;
  new_capacity *= kLine;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(new_capacity);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(new_capacity, new_capacity);
  mean.head(dim_) = mean_.head(dim_);
  cov.topLeftCorner(dim_, dim_) = cov_.topLeftCorner(dim_, dim_);
  mean_.swap(mean);
  cov_.swap(cov);
}

int SlamState::AppendStates(int count) {
  Reserve(dim_ + count);
  const int first = dim_;
  dim_ += count;
  return first;
}

Eigen::Vector2d SlamState::velocity(int k) const {
  const StateObject& o = object(k);
  if (!o.has_velocity()) return Eigen::Vector2d::Zero();
  return mean_.segment<2>(o.velocity_index);
}

Eigen::Matrix4d SlamState::ObjectCovariance(int k) const {
  const StateObject& o = object(k);
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  const int p = o.position_index;
  c.topLeftCorner<2, 2>() = cov_.block<2, 2>(p, p);
  if (o.has_velocity()) {
    const int v = o.velocity_index;
    c.topRightCorner<2, 2>() = cov_.block<2, 2>(p, v);
    c.bottomLeftCorner<2, 2>() = cov_.block<2, 2>(v, p);
    c.bottomRightCorner<2, 2>() = cov_.block<2, 2>(v, v);
  }
  return c;
}

int SlamState::AppendCorrelatedPair(const Eigen::Vector2d& value,
                                    const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                                    const Eigen::Matrix2d& independent_covariance) {
  ++revision_;
  const int old_dim = dim_;
  const int p = AppendStates(2);
  SetCorrelatedPair(p, value, jacobian_robot, independent_covariance, old_dim);
  return p;
}

void SlamState::SetCorrelatedPair(int p, const Eigen::Vector2d& value,
                                  const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                                  const Eigen::Matrix2d& independent_covariance, int columns) {
  mean_.segment<2>(p) = value;
  // Cross covariance with the first `columns` states, the heading drift included: G * P_r,x
  // (rows 0-2 of P: the pose).
  const Eigen::MatrixXd cross = jacobian_robot * cov_.topLeftCorner(kRobotPoseDim, columns);
  cov_.block(p, 0, 2, columns) = cross;
  cov_.block(0, p, columns, 2) = cross.transpose();
  const Eigen::Matrix2d own = jacobian_robot * cov_.topLeftCorner<3, 3>() *
                                  jacobian_robot.transpose() +
                              independent_covariance;
  cov_.block<2, 2>(p, p) = 0.5 * (own + own.transpose());
}

int SlamState::AddObject(const Eigen::Vector2d& position,
                         const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                         const Eigen::Matrix2d& independent_covariance,
                         const ObjectRecord& record) {
  StateObject object;
  object.position_index = AppendCorrelatedPair(position, jacobian_robot, independent_covariance);
  object.first_estimate_m = position;
  object.record = record;
  objects_.push_back(object);
  return num_objects() - 1;
}

int SlamState::AddLine(const Eigen::Vector2d& line,
                       const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                       const Eigen::Matrix2d& independent_covariance, const LineRecord& record) {
  StateLine added;
  added.param_index = AppendCorrelatedPair(line, jacobian_robot, independent_covariance);
  added.record = record;
  lines_.push_back(added);
  return num_lines() - 1;
}

void SlamState::RestartObject(int k, const Eigen::Vector2d& position,
                              const Eigen::Matrix<double, 2, 3>& jacobian_robot,
                              const Eigen::Matrix2d& independent_covariance,
                              const Eigen::Matrix2d& velocity_covariance) {
  ++revision_;
  StateObject& o = object(k);
  const int p = o.position_index;
  // As a new object, against every state; the object's velocity and anchor rows are set below.
  SetCorrelatedPair(p, position, jacobian_robot, independent_covariance, dim_);
  if (o.has_velocity()) {
    const int v = o.velocity_index;
    mean_.segment<2>(v).setZero();
    cov_.block(v, 0, 2, dim_).setZero();
    cov_.block(0, v, dim_, 2).setZero();
    cov_.block<2, 2>(v, v) = 0.5 * (velocity_covariance + velocity_covariance.transpose());
  }
  if (o.has_anchor()) {
    const int a = o.anchor_index;
    mean_.segment<2>(a) = position;
    const Eigen::MatrixXd position_rows = cov_.block(p, 0, 2, dim_);
    cov_.block(a, 0, 2, dim_) = position_rows;
    cov_.block(0, a, dim_, 2) = position_rows.transpose();
    cov_.block<2, 2>(a, a) = cov_.block<2, 2>(p, p);
    cov_.block<2, 2>(p, a) = cov_.block<2, 2>(p, p);
    cov_.block<2, 2>(a, p) = cov_.block<2, 2>(p, p);
  }
  o.first_estimate_m = position;
}

void SlamState::AddVelocity(int k, const Eigen::Vector2d& velocity,
                            const Eigen::Matrix2d& covariance) {
  if (object(k).has_velocity()) return;
  ++revision_;
  const int v = AppendStates(2);
  mean_.segment<2>(v) = velocity;
  cov_.block(v, 0, 2, v).setZero();
  cov_.block(0, v, v, 2).setZero();
  cov_.block<2, 2>(v, v) = 0.5 * (covariance + covariance.transpose());
  object(k).velocity_index = v;
}

void SlamState::RemoveVelocityAssumingZero(int k) {
  StateObject& o = object(k);
  if (!o.has_velocity()) return;
  ++revision_;
  const int v = o.velocity_index;
  const Eigen::Matrix2d pvv = cov_.block<2, 2>(v, v);
  Eigen::LLT<Eigen::Matrix2d> llt(pvv);
  if (llt.info() == Eigen::Success) {
    // Perfect pseudo-measurement v = 0: x -= P_xv Pvv^-1 v, P -= P_xv Pvv^-1 P_vx, computed as
    // a symmetric rank-2 downdate with W = P_xv L^-T.
    Eigen::MatrixXd w_transposed = cov_.block(v, 0, 2, dim_);
    llt.matrixL().solveInPlace(w_transposed);
    const Eigen::Vector2d whitened = llt.matrixL().solve(mean_.segment<2>(v));
    mean_.head(dim_).noalias() -= w_transposed.transpose() * whitened;
    SubtractSymmetricProduct(w_transposed);
  }
  // (A non-positive-definite Pvv means the velocity is already known exactly: dropping the
  // states is then the whole operation.)
  RemoveStates({v, v + 1});
  o.velocity_index = -1;
  // A static landmark from now on: its first estimate as one is where it is now.
  o.first_estimate_m = mean_.segment<2>(o.position_index);
}

void SlamState::AddStationaryAnchor(int k) {
  if (object(k).has_anchor()) return;
  ++revision_;
  const int p = object(k).position_index;
  const int a = AppendStates(2);
  mean_.segment<2>(a) = mean_.segment<2>(p);
  cov_.block(a, 0, 2, a) = cov_.block(p, 0, 2, a);
  cov_.block(0, a, a, 2) = cov_.block(0, p, a, 2);
  cov_.block<2, 2>(a, a) = cov_.block<2, 2>(p, p);
  object(k).anchor_index = a;
}

bool SlamState::ConditionOnAnchorAndRemoveIt(int k, double gate_chi2) {
  const StateObject& o = object(k);
  if (!o.has_anchor()) return false;
  const int p = o.position_index;
  const int a = o.anchor_index;
  // The displacement d = position - anchor, H = [.. I .. -I ..]: P H^T = P_:p - P_:a and
  // S = P_pp + P_aa - P_pa - P_ap.
  const Eigen::MatrixXd ph_transposed_t = cov_.block(p, 0, 2, dim_) - cov_.block(a, 0, 2, dim_);
  const Eigen::Matrix2d s = ph_transposed_t.block<2, 2>(0, p) - ph_transposed_t.block<2, 2>(0, a);
  const Eigen::Vector2d displacement = mean_.segment<2>(p) - mean_.segment<2>(a);
  Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (s + s.transpose()));
  bool conditioned = false;
  if (llt.info() == Eigen::Success) {
    const Eigen::Vector2d whitened = llt.matrixL().solve(displacement);
    if (whitened.squaredNorm() < gate_chi2) {
      ++revision_;
      Eigen::MatrixXd w_transposed = ph_transposed_t;
      llt.matrixL().solveInPlace(w_transposed);
      mean_.head(dim_).noalias() -= w_transposed.transpose() * whitened;
      SubtractSymmetricProduct(w_transposed);
      conditioned = true;
    }
  }
  // (A non-positive-definite S: the displacement is known exactly, nothing to condition on.)
  RemoveAnchor(k);
  return conditioned;
}

void SlamState::RemoveAnchor(int k) {
  StateObject& o = object(k);
  if (!o.has_anchor()) return;
  ++revision_;
  const int a = o.anchor_index;
  o.anchor_index = -1;
  RemoveStates({a, a + 1});
}

void SlamState::RemoveObjects(std::vector<int> object_indices) {
  std::sort(object_indices.begin(), object_indices.end());
  object_indices.erase(std::unique(object_indices.begin(), object_indices.end()),
                       object_indices.end());
  if (object_indices.empty()) return;
  ++revision_;
  std::vector<int> states;
  for (int k : object_indices) {
    const StateObject& o = object(k);
    states.push_back(o.position_index);
    states.push_back(o.position_index + 1);
    if (o.has_velocity()) {
      states.push_back(o.velocity_index);
      states.push_back(o.velocity_index + 1);
    }
    if (o.has_anchor()) {
      states.push_back(o.anchor_index);
      states.push_back(o.anchor_index + 1);
    }
  }
  std::vector<StateObject> kept;
  kept.reserve(objects_.size() - object_indices.size());
  size_t next_removed = 0;
  for (int k = 0; k < num_objects(); ++k) {
    if (next_removed < object_indices.size() && object_indices[next_removed] == k) {
      ++next_removed;
      continue;
    }
    kept.push_back(objects_[static_cast<size_t>(k)]);
  }
  objects_.swap(kept);
  std::sort(states.begin(), states.end());
  RemoveStates(states);
}

void SlamState::RemoveStates(const std::vector<int>& sorted_state_indices) {
  if (sorted_state_indices.empty()) return;
  // new_index[i] for every old state index (-1 when removed).
  std::vector<int> new_index(static_cast<size_t>(dim_), 0);
  for (int i : sorted_state_indices) new_index[static_cast<size_t>(i)] = -1;
  int next = 0;
  for (int i = 0; i < dim_; ++i) {
    if (new_index[static_cast<size_t>(i)] == 0) new_index[static_cast<size_t>(i)] = next++;
  }
  const int new_dim = next;
  // Column by column in increasing order, gathering the kept rows of each kept column: every
  // destination (row and column) is at or before its source, so nothing still to be read is
  // overwritten, and every access runs down a column (contiguous).
  std::vector<int> kept;
  kept.reserve(static_cast<size_t>(new_dim));
  for (int i = 0; i < dim_; ++i) {
    if (new_index[static_cast<size_t>(i)] >= 0) kept.push_back(i);
  }
  for (int to = 0; to < new_dim; ++to) {
    const int from = kept[static_cast<size_t>(to)];
    double* destination = cov_.col(to).data();
    const double* source = cov_.col(from).data();
    for (int r = 0; r < new_dim; ++r) destination[r] = source[kept[static_cast<size_t>(r)]];
    mean_(to) = mean_(from);
  }
  dim_ = new_dim;
  for (StateObject& o : objects_) {
    o.position_index = new_index[static_cast<size_t>(o.position_index)];
    if (o.has_velocity()) o.velocity_index = new_index[static_cast<size_t>(o.velocity_index)];
    if (o.has_anchor()) o.anchor_index = new_index[static_cast<size_t>(o.anchor_index)];
  }
  for (StateLine& l : lines_) l.param_index = new_index[static_cast<size_t>(l.param_index)];
}

void SlamState::SubtractSymmetricProduct(const Eigen::MatrixXd& v_transposed) {
  // Eigen's triangular product on the lower triangle, then the mirror: measured faster than
  // column panels that compute and mirror each panel while it is in cache (bench_estimator
  // BM_UpdateBatch, 330 observations: 21 ms against 22.5 ms CPU).
  ++revision_;
  auto cov = cov_.topLeftCorner(dim_, dim_);
  cov.selfadjointView<Eigen::Lower>().rankUpdate(v_transposed.transpose(), -1.0);
  MirrorLowerTriangle();
}

void SlamState::MirrorLowerTriangle() {
  // Tile by tile, so that the strided reads of rows stay within a few cache lines per tile
  // (a row-at-a-time copy touches a new cache line on every element).
  ++revision_;
  constexpr int kTile = 32;
  for (int column_start = 0; column_start < dim_; column_start += kTile) {
    const int columns = std::min(kTile, dim_ - column_start);
    // Diagonal tile: element by element above its diagonal.
    for (int j = column_start + 1; j < column_start + columns; ++j) {
      for (int i = column_start; i < j; ++i) cov_(i, j) = cov_(j, i);
    }
    // Tiles above the diagonal tile in this column band, from their mirror images below.
    for (int row_start = 0; row_start < column_start; row_start += kTile) {
      const int rows = std::min(kTile, column_start - row_start);
      cov_.block(row_start, column_start, rows, columns) =
          cov_.block(column_start, row_start, columns, rows).transpose();
    }
  }
}

}  // namespace slammtt
