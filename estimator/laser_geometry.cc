#include "estimator/laser_geometry.h"

#include <cmath>
#include <sstream>
#include <vector>

namespace slammtt {
namespace {

double Degrees(double rad) { return rad * 180.0 / M_PI; }

std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string DescribeMount(const SensorMount& m) {
  return "mount forward " + Number(m.forward_m) + " m, left " + Number(m.left_m) + " m, yaw " +
         Number(Degrees(m.yaw_rad)) + " deg";
}

std::string DescribeView(const FieldOfView& v) {
  return "field of view " + Number(Degrees(v.start_rad)) + " to " + Number(Degrees(v.end_rad)) +
         " deg";
}

std::string DescribeRange(double max_range_m) { return "max range " + Number(max_range_m) + " m"; }

bool MountsAgree(const SensorMount& a, const SensorMount& b) {
  return std::abs(a.forward_m - b.forward_m) <= kGeometryLengthTolerance_m &&
         std::abs(a.left_m - b.left_m) <= kGeometryLengthTolerance_m &&
         std::abs(a.yaw_rad - b.yaw_rad) <= kGeometryAngleTolerance_rad;
}

bool ViewsAgree(const FieldOfView& a, const FieldOfView& b) {
  // Two full circles agree wherever they start.
  if (a.full() && b.full()) return true;
  return std::abs(a.start_rad - b.start_rad) <= kGeometryAngleTolerance_rad &&
         std::abs(a.end_rad - b.end_rad) <= kGeometryAngleTolerance_rad;
}

std::string Join(const std::vector<std::string>& parts) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : "; ") + part;
  return text;
}

// The part's description without its leading name ("forward 0.1 m, ..." for "mount ...").
std::string Value(const std::string& description, const std::string& name) {
  return description.substr(name.size() + 1);
}

// A value of several numbers in parentheses, so that the line reads unambiguously.
std::string Grouped(const std::string& value) {
  return value.find(',') == std::string::npos ? value : "(" + value + ")";
}

std::string Disagreement(const std::string& name, const std::string& configured,
                         const std::string& log) {
  return name + ": configuration " + Grouped(Value(configured, name)) + ", log " +
         Grouped(Value(log, name));
}

}  // namespace

LaserGeometry LaserGeometryOf(const EstimatorOptions& options) {
  LaserGeometry geometry;
  geometry.mount = options.sensor;
  geometry.view = FieldOfViewOf(options);
  geometry.max_range_m = options.max_range_m;
  return geometry;
}

std::string LaserGeometryProblem(const LaserGeometry& g) {
  const double values[] = {g.mount.forward_m, g.mount.left_m, g.mount.yaw_rad,
                           g.view.start_rad, g.view.end_rad};
  for (const double v : values) {
    if (!std::isfinite(v)) return "a value is not a finite number";
  }
  if (std::abs(g.mount.yaw_rad) > M_PI) return "mount yaw beyond [-180, 180] deg";
  if (!(g.view.end_rad > g.view.start_rad) ||
      g.view.end_rad - g.view.start_rad > 2.0 * M_PI + 1e-12) {
    return "field of view end not after its start, or more than 360 deg after it";
  }
  if (std::abs(g.view.start_rad) > 2.0 * M_PI || std::abs(g.view.end_rad) > 2.0 * M_PI) {
    return "field of view beyond [-360, 360] deg";
  }
  if (!(g.max_range_m > 0.0)) return "max range not positive";  // NaN too; +inf: none stated
  return "";
}

std::string DescribeLaserGeometry(const LaserGeometry& g) {
  return Join({DescribeMount(g.mount), DescribeView(g.view), DescribeRange(g.max_range_m)});
}

GeometryReconciliation ReconcileLaserGeometry(const EstimatorOptions& configured,
                                              const ConfiguredGeometryParts& given,
                                              const LaserGeometry& log) {
  GeometryReconciliation result;
  result.options = configured;
  result.problem = LaserGeometryProblem(log);
  if (!result.problem.empty()) return result;

  const LaserGeometry mine = LaserGeometryOf(configured);
  std::vector<std::string> taken;
  std::vector<std::string> disagree;
  EstimatorOptions options = configured;
  if (given.mount) {
    if (!MountsAgree(mine.mount, log.mount)) {
      disagree.push_back(
          Disagreement("mount", DescribeMount(mine.mount), DescribeMount(log.mount)));
    }
  } else {
    options.sensor = log.mount;
    taken.push_back(DescribeMount(log.mount));
  }
  if (given.field_of_view) {
    if (!ViewsAgree(mine.view, log.view)) {
      disagree.push_back(Disagreement("field of view", DescribeView(mine.view),
                                      DescribeView(log.view)));
    }
  } else {
    if (log.view.start_rad == -log.view.end_rad) {
      // As a configuration writes a centred view: the same expressions judge it
      // (field_of_view.h), so the estimate is the configured one bit for bit.
      options.field_of_view_rad = log.view.end_rad - log.view.start_rad;
      options.field_of_view_start_rad = 0.0;
      options.field_of_view_end_rad = 0.0;
    } else {
      options.field_of_view_rad = 2.0 * M_PI;  // the default, which start / end require
      options.field_of_view_start_rad = log.view.start_rad;
      options.field_of_view_end_rad = log.view.end_rad;
    }
    taken.push_back(DescribeView(log.view));
  }
  if (std::isinf(log.max_range_m)) {
    // A laser without a stated limit (REP 117 allows range_max = +inf): the range stays the
    // configured one, whether or not the configuration gives it.
  } else if (given.max_range) {
    if (std::abs(mine.max_range_m - log.max_range_m) > kGeometryLengthTolerance_m) {
      disagree.push_back(Disagreement("max range", DescribeRange(mine.max_range_m),
                                      DescribeRange(log.max_range_m)));
    }
  } else {
    options.max_range_m = log.max_range_m;
    taken.push_back(DescribeRange(log.max_range_m));
  }
  result.disagreement = Join(disagree);
  const std::string problem = CheckEstimatorOptions(options);
  if (!problem.empty()) {
    result.problem = "with it the options are not usable: " + problem;
    return result;
  }
  result.options = options;
  result.taken = Join(taken);
  return result;
}

}  // namespace slammtt
