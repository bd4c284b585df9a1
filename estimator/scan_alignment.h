// The robot's motion from the static structure, for a robot that publishes no odometry: the
// scan's walls and posts aligned with the previous scan's (feature-level scan matching), the
// result fed to the prediction (scan_prediction.h) as an odometry increment would be.
//
// Without a motion input the prediction keeps the robot where it was, with the extrapolation
// noise; a moving robot then sees the whole scenery shift, and posts and wall ends that shifted
// by more than their gates become new objects that move (issue 13, item 5). Aligning the scan
// with the previous one measures the shift instead.
//
// The alignment (AlignScans) is iteratively reweighted Gauss-Newton over the increment
// x = (dx_m, dy_m, dheading_rad): the pose of the robot at this scan in the robot frame of the
// previous one, so that a point p of this scan lies at R(dheading) p + (dx, dy) in the previous
// frame. The residuals, re-associated at every iteration at the current x (ICP, Besl and McKay,
// "A method for registration of 3-D shapes", PAMI 14(2), 1992; point-to-line as in Censi's PLICP,
// "An ICP variant using a point-to-line metric", ICRA 2008):
//  - point to point: a point feature of this scan (not a person's centre: people move) and the
//    nearest point of the previous scan within match_m, 2 residuals, sigma point_sigma_m;
//  - point to line: both ends of a line feature's observed extent against a line of the previous
//    scan that is parallel within match_angle or within 3 sigmas of the two lines' direction
//    uncertainty, whichever is wider (either direction), whose distance is within match_m and
//    whose extent overlaps or lies within match_m, 1 residual per end (only the distance across
//    a wall is measured: the ends of a seen run move with occlusions and the field of view).
//    Its sigma is line_sigma_m widened by what the two lines' direction uncertainty does at that
//    end: the previous line's, times the end's distance from that line's middle, and the scan
//    line's own, times half its length (its ends are projected onto its fit). A short run far
//    away (a door jamb's face across a corridor, 0.4 m at 4 m: 4-5 degrees of direction noise)
//    so still measures the distance across it, which along a corridor is the only structure that
//    fixes the motion, without turning the robot by its tilt.
// The iterations start from the guess with its heading replaced by the heading change most of
// the scan's line length agrees on (TurnFromLines): a rotation about the robot leaves a line's
// distance from it unchanged, so the lines' angles give the turn before the translation is
// known, and the associations of the first iteration are made at the right heading even when
// the robot began to turn since the previous scan (the guess then is off by a whole scan's
// turn, beyond match_angle).
// Each residual r gets the Cauchy weight 1 / (1 + (r / (robust_scale sigma))^2), so that a leg
// that walked or a wrong association pulls little (Zhang, "Parameter estimation techniques: a
// tutorial with application to conic fitting", Image and Vision Computing 15(1), 1997, M-
// estimators). The guess (constant velocity) enters as a prior with its covariance, so that a
// direction no residual observes (along a single wall, along a corridor of two parallel walls)
// keeps the guess and the guess's large variance instead of a value the noise chose. The
// covariance is the inverse of the final information matrix (prior included) times
// covariance_scale (the residuals of one wall's two ends are not independent, and an
// association can be wrong).
//
// Bad input: a non-finite coordinate, or a segment shorter than kMinAlignmentSegment_m, is left
// out (counted in AlignmentScan::skipped). An empty scan or reference gives the guess and its
// covariance back (no residual).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/options_schema.h"
#include "estimator/line_landmarks.h"
#include "estimator/point_measurement.h"
#include "estimator/range_bearing_model.h"

namespace slammtt {

inline constexpr double kMinAlignmentSegment_m = 0.05;
// What one alignment may cost is bounded (docs/estimator.md, "Hostile sizes"): the nearest
// kMaxAlignmentPoints points and the longest kMaxAlignmentSegments lines of a scan are used.
// Far above a room's (office: at most 8 lines and a few points per scan).
inline constexpr int kMaxAlignmentPoints = 128;
inline constexpr int kMaxAlignmentSegments = 64;
inline constexpr double kMinCornerAngle_rad = 45.0 * M_PI / 180.0;
inline constexpr double kCornerGap_m = 0.15;

struct ScanAlignmentOptions {
  // On: a robot with no odometry (no ODOMETRY received since the estimator started) moves by
  // the alignment of consecutive scans. With odometry nothing changes whether on or off.
  bool enabled = true;
  int max_iterations = 10;
  double match_m = 0.3;                          // association distance at the current guess
  double match_angle_rad = 5.0 * M_PI / 180.0;   // lines parallel within
  double point_sigma_m = 0.03;                   // per coordinate of a point-to-point residual
  double line_sigma_m = 0.02;                    // of a point-to-line residual
  double robust_scale = 2.0;                     // Cauchy scale, in sigmas
  double covariance_scale = 1.0;                 // the information's inverse times this
  // The constant-velocity guess's prior: sigmas of the change of speed and of turn rate since
  // the previous scan, per second. A P3-DX turns from straight to 60 deg/s within one scan.
  double guess_speed_sigma_mps = 0.3;
  double guess_turn_sigma_radps = 60.0 * M_PI / 180.0;
  // The heading change the lines vote for is searched within this of the guess's.
  double max_turn_search_rad = 30.0 * M_PI / 180.0;
  // The velocity is filtered (0: off, the guess's prior is the fixed sigmas above): its
  // covariance (the last alignment's over its interval squared; guess_speed_sigma_mps and
  // guess_turn_sigma_radps before any alignment) is carried from scan to scan and grows by the
  // squares of these per second (a random walk of the velocity), and the guess's prior is it
  // times the interval squared. A direction no scan observes so keeps a velocity as uncertain
  // as it is, and one the scans measure keeps what they measured (office without odometry:
  // seeds 1-20 ATE ratio median 3.70 -> 2.82; docs/targets.md).
  double velocity_walk_mps2 = 0.3;
  double velocity_turn_walk_radps = 60.0 * M_PI / 180.0;
};

// The schema of these options (keys in EstimatorOptions' group `scan_alignment`; the ranges are
// the whole validation).
void VisitScanAlignmentOptions(OptionVisitor* visitor, ScanAlignmentOptions* options);

// The static-looking features of one scan in the robot frame.
struct AlignmentSegment {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  // Variance of its direction (the fit's alpha variance; 0: exact).
  double direction_var_rad2 = 0.0;
};
struct AlignmentScan {
  std::vector<Eigen::Vector2d> points_m;  // point features, then corners
  std::vector<AlignmentSegment> segments;
  int corners = 0;  // of points_m
  int skipped = 0;  // features left out: non-finite, or a segment too short
  int over_cap = 0;  // beyond kMaxAlignmentPoints / kMaxAlignmentSegments, left out
};

// The scan's point features that are not people, its line features' extents (their end points
// projected onto the fitted line, whose fit is better than the two end beams), and its corners
// as points: where two of its lines at more than kMinCornerAngle_rad to each other have ends
// within kCornerGap_m of each other, the lines' intersection (a corner of a room, a door jamb:
// the static structure that fixes the motion along a corridor, which its walls cannot; the end
// of a lone run moves with occlusions and is not used). Placed in the robot frame by the sensor
// mount (eq. 11 and its yaw). The caps apply before the corners are found (ties: input order).
AlignmentScan AlignmentScanOf(const std::vector<PointMeasurement>& points,
                              const std::vector<LineReading>& lines, const SensorMount& mount);

struct ScanAlignment {
  Eigen::Vector3d increment = Eigen::Vector3d::Zero();  // (dx_m, dy_m, dheading_rad)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  int point_pairs = 0;  // associations at the last iteration
  int line_pairs = 0;
  int iterations = 0;
};

// The heading change (within max_turn_search of guess_heading_rad) that the most line length
// agrees on within kTurnVoteWidth_rad: each pair of a line of `scan` and one of `reference` at
// about the same distance from the robot (within match_m plus guess_shift_m) votes for the
// angle between them with the shorter one's length. nullopt with under kMinTurnVote_m of
// agreeing length.
inline constexpr double kTurnVoteWidth_rad = 1.0 * M_PI / 180.0;
inline constexpr double kMinTurnVote_m = 1.0;
std::optional<double> TurnFromLines(const AlignmentScan& reference, const AlignmentScan& scan,
                                    double guess_heading_rad, double guess_shift_m,
                                    const ScanAlignmentOptions& options);

// Aligns `scan` with `reference` from `guess` (prior covariance `guess_covariance`, positive
// definite), as the header says.
ScanAlignment AlignScans(const AlignmentScan& reference, const AlignmentScan& scan,
                         const Eigen::Vector3d& guess, const Eigen::Matrix3d& guess_covariance,
                         const ScanAlignmentOptions& options);

// Consecutive scans of a robot without odometry: keeps the previous scan and the robot's last
// velocity, and gives the motion from the previous scan to the next. The velocity is the last
// alignment's increment over its interval: the motion the structure measured. Not the change
// of the poses the estimator ended the scans with: a correction of the map (a landmark that
// pulls the robot 5 cm) is a jump, not a speed, and extrapolated along a corridor where no scan
// observes the motion it ran away (corridor seed 1 without odometry: 0.36 m in 0.6 s at 54 s,
// ATE 0.31 m; from the increments 0.07 m).
class ScanToScanMotion {
 public:
  // The motion from the previous scan (Keep) to `scan`, dt_s later: the alignment from the
  // constant-velocity guess, whose prior sigmas are guess_speed_sigma_mps * dt_s for each
  // coordinate and guess_turn_sigma_radps * dt_s for the heading. nullopt before the first
  // Keep.
  std::optional<ScanAlignment> MotionTo(const AlignmentScan& scan, double dt_s,
                                        const ScanAlignmentOptions& options) const;
  // `scan` becomes the reference at utime. The velocity: `aligned`'s increment (the alignment
  // of this scan with the previous one) over the time since the previous Keep; without one
  // (null: the first scans, an alignment that was not made), the change of `pose` (map frame,
  // where the estimator left the robot) over that time.
  void Keep(AlignmentScan scan, const Eigen::Vector3d& pose, int64_t utime,
            const ScanAlignment* aligned = nullptr);
  void Clear();

 private:
  std::optional<AlignmentScan> reference_;
  Eigen::Vector3d pose_ = Eigen::Vector3d::Zero();
  int64_t utime_ = 0;
  // In the robot frame: (forward, left, turn) per second.
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  // The velocity's covariance (velocity_walk_mps2 > 0); a negative (0, 0): not measured yet.
  Eigen::Matrix3d velocity_covariance_ = -Eigen::Matrix3d::Identity();
};

}  // namespace slammtt
