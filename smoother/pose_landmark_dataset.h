// Pose-landmark problems in the text format of Victoria Park
// (../shared/data/real/victoria_park/SOURCE.md), read from a stream, and fed to a Smoother
// keyframe by keyframe. One measurement a line; pose and landmark ids are whole numbers:
//   ODOMETRY i j dx dy dtheta  C11 C12 C13 C22 C23 C33
//   LANDMARK i l dx dy  C11 C12 C22
// ODOMETRY: pose j in pose i's frame; LANDMARK: landmark l's position in pose i's frame. The six
// (three) numbers are the upper triangle of the measurement's covariance: that is how GTSAM's
// load2D reads this file (gtsam/slam/dataset.cpp, NoiseFormatAUTO picks NoiseFormatCOV for the
// pattern "a 0 0 b 0 c", the pattern of every line of Victoria Park), and the only reading in
// which the odometry is plausible (sigma 0.01 m, 0.002 rad per step; read as information it
// would be 100 m). The comparison with GTSAM (scripts/compare-victoria-park.py) needs the same
// problem on both sides.
//
// Two readings of a LANDMARK line (LandmarkReading):
// - kBearingRange, load2D's: a range-bearing factor (no mount offset) with range = |(dx, dy)|,
//   bearing = atan2(dy, dx), sigma_range = sqrt(C11), sigma_bearing = sqrt(C11 / 10) when
//   |C11 - C22| < 1e-4, else both 1 (load2D's rule: the x-y covariance taken as the
//   uncertainty at 10 m);
// - kRelativePosition, the file's own: a relative-position factor with covariance
//   [C11 C12; C12 C22].
//
// A line that is not one of the two, a number that is not finite, a count of fields other than
// the format's, a covariance that is not positive definite: an error naming the line.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "smoother/smoother.h"

namespace slammtt {

struct PoseLandmarkDataset {
  struct Odometry {
    int64_t from = 0;
    int64_t to = 0;
    Eigen::Vector3d relative = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  };
  struct Observation {
    int64_t pose = 0;
    int64_t landmark = 0;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // in the pose's frame, m
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  };
  // One keyframe: a new pose reached by one odometry line (none for the first pose) and the
  // observations that follow it in the file.
  struct Keyframe {
    int64_t pose = 0;
    std::optional<int> odometry;  // index into `odometry`
    std::vector<int> observations;
  };
  std::vector<Odometry> odometry;
  std::vector<Observation> observations;
  std::vector<Keyframe> keyframes;  // in file order
};

struct DatasetParseResult {
  std::optional<PoseLandmarkDataset> dataset;
  std::string error;  // "line N: ..." when dataset is empty
};

// Reads the whole stream. Observations before any odometry belong to the first keyframe, whose
// pose is the first ODOMETRY's i (or the first LANDMARK's i in a file without odometry).
// Odometry must continue the chain (i = the previous line's j) and j must be new.
DatasetParseResult ParsePoseLandmarkDataset(std::istream& text);

enum class LandmarkReading { kBearingRange, kRelativePosition };

// Adds keyframe k to the smoother: its pose, initialised by composing the odometry with the
// smoother's current estimate of the previous pose (the first pose at the origin with a prior
// of sigma first_pose_sigma in x, y and theta), its odometry factor, its observations, and
// each landmark seen for the first time, initialised from its first observation. Feeding every
// keyframe before any solve puts the whole problem at the odometry chain.
std::optional<std::string> AddKeyframe(const PoseLandmarkDataset& dataset, size_t k,
                                       LandmarkReading reading, Smoother* smoother,
                                       double first_pose_sigma = 1e-3);

}  // namespace slammtt
