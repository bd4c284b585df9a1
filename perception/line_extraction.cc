#include "perception/line_extraction.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "common/angle.h"

namespace slammtt {
namespace {

// Largest distance of the points [begin, end) from the chord between the run's end points, and
// where it is (the first such point). A run whose ends coincide measures from that point.
double FarthestFromChord(const double* x, const double* y, size_t begin, size_t end,
                         size_t* farthest) {
  const size_t last = end - 1;
  const double dx = x[last] - x[begin];
  const double dy = y[last] - y[begin];
  const double length2 = dx * dx + dy * dy;
  double best = 0.0;
  *farthest = begin;
  if (length2 > 1e-18) {
    const double inv_length = 1.0 / std::sqrt(length2);
    for (size_t i = begin + 1; i < last; ++i) {
      const double d = std::abs((x[i] - x[begin]) * dy - (y[i] - y[begin]) * dx) * inv_length;
      if (d > best) {
        best = d;
        *farthest = i;
      }
    }
  } else {
    for (size_t i = begin + 1; i < last; ++i) {
      const double d = std::hypot(x[i] - x[begin], y[i] - y[begin]);
      if (d > best) {
        best = d;
        *farthest = i;
      }
    }
  }
  return best;
}

}  // namespace

double MaxDistanceFromChord(const double* x_m, const double* y_m, size_t count) {
  if (count < 3) return 0.0;
  size_t farthest = 0;
  return FarthestFromChord(x_m, y_m, 0, count, &farthest);
}

Eigen::Vector2d Centroid(const double* x_m, const double* y_m, size_t count) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < count; ++i) sum += Eigen::Vector2d(x_m[i], y_m[i]);
  return count > 0 ? Eigen::Vector2d(sum / static_cast<double>(count)) : sum;
}

CircleFit FitCircleKasa(const double* x_m, const double* y_m, size_t count) {
  CircleFit fit;
  if (count < 3) return fit;
  const Eigen::Vector2d centroid = Centroid(x_m, y_m, count);
  const double mx = centroid.x();
  const double my = centroid.y();
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < count; ++i) {
    const double u = x_m[i] - mx;
    const double v = y_m[i] - my;
    const Eigen::Vector3d row(u, v, 1.0);
    a.noalias() += row * row.transpose();
    b.noalias() -= row * (u * u + v * v);
  }
  const Eigen::Vector3d solution = a.ldlt().solve(b);
  if (!solution.allFinite()) return fit;
  const double cu = -0.5 * solution(0);
  const double cv = -0.5 * solution(1);
  const double r2 = cu * cu + cv * cv - solution(2);
  if (!(r2 > 0.0)) return fit;
  fit.radius_m = std::sqrt(r2);
  fit.centre_x_m = mx + cu;
  fit.centre_y_m = my + cv;
  double sum = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const double e = std::hypot(x_m[i] - fit.centre_x_m, y_m[i] - fit.centre_y_m) - fit.radius_m;
    sum += e * e;
  }
  fit.rms_residual_m = std::sqrt(sum / static_cast<double>(count));
  fit.ok = std::isfinite(fit.rms_residual_m) && std::isfinite(fit.radius_m);
  if (!fit.ok) fit = CircleFit{};
  return fit;
}

LineFit FitLine(const double* x_m, const double* y_m, size_t count, double range_sigma_m,
                double bearing_sigma_rad) {
  LineFit fit;
  fit.covariance = 1e6 * Eigen::Matrix2d::Identity();
  if (count == 0) return fit;
  const double n = static_cast<double>(count);
  const Eigen::Vector2d centroid = Centroid(x_m, y_m, count);
  const double mx = centroid.x();
  const double my = centroid.y();
  fit.centroid_x_m = mx;
  fit.centroid_y_m = my;
  double sxx = 0.0;
  double syy = 0.0;
  double sxy = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const double dx = x_m[i] - mx;
    const double dy = y_m[i] - my;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  if (count < 2 || !(sxx + syy > 1e-18)) {  // one place: no direction
    fit.alpha_rad = std::atan2(my, mx);
    fit.rho_m = std::hypot(mx, my);
    return fit;
  }
  // The normal minimises sum ((p_i - c) . n)^2: 2 alpha = atan2(-2 Sxy, Syy - Sxx).
  double alpha = 0.5 * std::atan2(-2.0 * sxy, syy - sxx);
  double ca = std::cos(alpha);
  double sa = std::sin(alpha);
  double rho = mx * ca + my * sa;
  if (rho < 0.0) {  // the normal points from the sensor towards the line
    rho = -rho;
    alpha += M_PI;
    ca = -ca;
    sa = -sa;
  }
  fit.alpha_rad = WrapAngle(alpha);
  fit.rho_m = rho;
  // Direction along the line, t = d n / d alpha.
  const double tx = -sa;
  const double ty = ca;
  double sum_e2 = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const double e = x_m[i] * ca + y_m[i] * sa - rho;
    sum_e2 += e * e;
  }
  fit.rms_residual_m = std::sqrt(sum_e2 / n);
  const double range_var = range_sigma_m * range_sigma_m;
  const double bearing_var = bearing_sigma_rad * bearing_sigma_rad;
  // The sensor model's variance of each point's error perpendicular to the line...
  const auto model_variance = [&](double x, double y) {
    const double along_normal = x * ca + y * sa;  // r cos(phi)
    const double r2 = x * x + y * y;
    const double cos2 = r2 > 0.0 ? along_normal * along_normal / r2 : 1.0;
    return range_var * cos2 + bearing_var * (r2 - along_normal * along_normal);
  };
  double model_sum = 0.0;
  for (size_t i = 0; i < count; ++i) model_sum += model_variance(x_m[i], y_m[i]);
  // ...scaled up when the fit's own scatter (unbiased: n - 2 degrees of freedom) says the
  // surface or the sensor is rougher than the model.
  const double scatter = count > 2 ? sum_e2 / (n - 2.0) : 0.0;
  const double model_mean = model_sum / n;
  const double scale = model_mean > 0.0 ? std::max(1.0, scatter / model_mean) : 1.0;
  double sum_s2 = 0.0;     // S
  double sum_var = 0.0;    // sum sigma_i^2
  double sum_s2var = 0.0;  // sum s_i^2 sigma_i^2
  double sum_svar = 0.0;   // sum s_i sigma_i^2
  for (size_t i = 0; i < count; ++i) {
    const double x = x_m[i];
    const double y = y_m[i];
    const double var = std::max(scale * model_variance(x, y), 1e-12);
    const double s = (x - mx) * tx + (y - my) * ty;
    sum_s2 += s * s;
    sum_var += var;
    sum_s2var += s * s * var;
    sum_svar += s * var;
  }
  if (!(sum_s2 > 1e-18)) return fit;
  const double var_alpha = sum_s2var / (sum_s2 * sum_s2);
  const double var_d = sum_var / (n * n);
  const double cov_d_alpha = -sum_svar / (n * sum_s2);
  const double tc = tx * mx + ty * my;
  fit.covariance(0, 0) = var_d + 2.0 * tc * cov_d_alpha + tc * tc * var_alpha;
  fit.covariance(1, 1) = var_alpha;
  fit.covariance(0, 1) = cov_d_alpha + tc * var_alpha;
  fit.covariance(1, 0) = fit.covariance(0, 1);
  return fit;
}

void SplitAndMerge(const double* x_m, const double* y_m, size_t count, double split_distance_m,
                   std::vector<PointRun>* runs, std::vector<PointRun>* stack) {
  runs->clear();
  stack->clear();
  if (count == 0) return;
  // Split: depth first, right half pushed first so that runs come out in point order. A split
  // at point k gives [begin, k + 1) and [k, end): the corner point belongs to both lines.
  stack->push_back(PointRun{0, count});
  while (!stack->empty()) {
    const PointRun run = stack->back();
    stack->pop_back();
    size_t farthest = run.begin;
    if (run.size() > 2 &&
        FarthestFromChord(x_m, y_m, run.begin, run.end, &farthest) > split_distance_m) {
      stack->push_back(PointRun{farthest, run.end});
      stack->push_back(PointRun{run.begin, farthest + 1});
    } else {
      runs->push_back(run);
    }
  }
  // Merge: neighbours whose union is straight by the same test become one run.
  size_t kept = 0;
  for (size_t k = 1; k < runs->size(); ++k) {
    PointRun& current = (*runs)[kept];
    const PointRun& next = (*runs)[k];
    size_t farthest = 0;
    const PointRun united{current.begin, next.end};
    if (FarthestFromChord(x_m, y_m, united.begin, united.end, &farthest) <= split_distance_m) {
      current = united;
    } else {
      (*runs)[++kept] = next;
    }
  }
  runs->resize(kept + 1);
}

void FitRangesOfRuns(const std::vector<PointRun>& runs, bool leave_out_shared_corners,
                     std::vector<FitRange>* fits) {
  fits->resize(runs.size());
  for (size_t k = 0; k < runs.size(); ++k) (*fits)[k] = FitRange{runs[k].begin, runs[k].end};
  if (!leave_out_shared_corners) return;
  for (size_t k = 0; k + 1 < runs.size(); ++k) {
    if (runs[k].end != runs[k + 1].begin + 1) continue;
    if ((*fits)[k].fit_end - (*fits)[k].fit_begin >= 3) (*fits)[k].fit_end -= 1;
    if ((*fits)[k + 1].fit_end - (*fits)[k + 1].fit_begin >= 3) (*fits)[k + 1].fit_begin += 1;
  }
}

}  // namespace slammtt
