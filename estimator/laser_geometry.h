// The laser's geometry as the estimator uses it (where it sits on the robot, what it sees) and
// how a geometry that a log carries (LASER_GEOMETRY, laser_geometry_t) meets the one the
// configuration gives.
//
// The geometry is written where it is known: the scenario of the synthetic world, the RPLIDAR
// driver's section, the transforms of an imported bag. Their publishers put it in the log, so
// that an estimator without those keys in its configuration (slammtt-replay without --config)
// estimates with the sensor that made the log instead of silently with the defaults (which on
// s2-lobby gave a static recall of 0.455 instead of 1.0). Three parts, each taken or compared
// on its own:
//   mount          sensor_forward_m, sensor_left_m, sensor_yaw_deg
//   field of view  field_of_view_deg, or field_of_view_start_deg / field_of_view_end_deg
//   range          max_range_m
// A part the configuration gives (any of its keys present) is kept and compared with the log;
// a part it does not give is taken from the log. A log whose max range is +inf (no stated
// limit) gives no range part. min_range_m is the estimator's own sanity gate
// on features (a feature is a cluster's centre, beyond the laser's nearest return), not a part.
#pragma once

#include <string>

#include "estimator/estimator_options.h"
#include "estimator/field_of_view.h"
#include "estimator/range_bearing_model.h"

namespace slammtt {

struct LaserGeometry {
  SensorMount mount;
  FieldOfView view;
  double max_range_m = 30.0;
};

// Which parts of the geometry the configuration gives (any of the part's keys present).
struct ConfiguredGeometryParts {
  bool mount = false;
  bool field_of_view = false;
  bool max_range = false;
  bool any() const { return mount || field_of_view || max_range; }
};

// Differences below these are agreement: a millimetre, and 0.05 degrees (a tenth of the
// coarsest beam spacing we ship, 0.9 degrees, and above the rounding of a configuration that
// writes degrees with three decimals).
inline constexpr double kGeometryLengthTolerance_m = 1e-3;
inline constexpr double kGeometryAngleTolerance_rad = 0.05 * M_PI / 180.0;

// The geometry the options hold (FieldOfViewOf for the view).
LaserGeometry LaserGeometryOf(const EstimatorOptions& options);

// Empty when `geometry` is usable, else one line why: a non-finite value, a mount yaw beyond
// [-pi, pi], a view whose end is not after its start or spans more than a turn or lies beyond
// [-2 pi, 2 pi], a max range that is not positive (NaN included; +inf is usable: none stated).
std::string LaserGeometryProblem(const LaserGeometry& geometry);

// What becomes of a log's geometry.
struct GeometryReconciliation {
  EstimatorOptions options;  // the configured options with the parts they do not give taken
  std::string taken;         // "" or the parts taken, with their values: "mount forward 0.1 m,
                             // left 0 m, yaw 0 deg; field of view -90 to 90 deg; max range 30 m"
  std::string disagreement;  // "" or every configured part off by more than the tolerance,
                             // with both values: "max range: configuration 12 m, log 30 m;
                             // mount: configuration (forward 0 m, ...), log (forward ...)"
  std::string problem;       // "" or why the log's geometry is not used (nothing is taken)
};

// Takes the parts of `log` that `given` does not hold into `configured` and compares the
// others. A view taken from the log that is centred on the heading (start = -end) is written
// as field_of_view_rad (start and end 0), as a configuration writes it, so that the estimate
// is the configured one to the last bit. problem is set, and the options stay `configured`,
// when the log's geometry is unusable (LaserGeometryProblem) or the options it gives are not
// (CheckEstimatorOptions, e.g. a max range below min_range_m).
GeometryReconciliation ReconcileLaserGeometry(const EstimatorOptions& configured,
                                              const ConfiguredGeometryParts& given,
                                              const LaserGeometry& log);

// "mount forward 0.1 m, left 0 m, yaw 0 deg; field of view -90 to 90 deg; max range 30 m"
std::string DescribeLaserGeometry(const LaserGeometry& geometry);

}  // namespace slammtt
