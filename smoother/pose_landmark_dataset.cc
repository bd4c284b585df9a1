#include "smoother/pose_landmark_dataset.h"

#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <unordered_set>

#include "common/number_text.h"
#include "geometry/pose2.h"

namespace slammtt {

namespace {

// Splits a line into whitespace-separated fields.
std::vector<std::string> Fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  std::string field;
  while (in >> field) fields.push_back(field);
  return fields;
}

bool ParseNumbers(const std::vector<std::string>& fields, size_t first, std::vector<double>* out) {
  out->clear();
  for (size_t k = first; k < fields.size(); ++k) {
    const std::optional<double> value = ParseFiniteDouble(fields[k]);
    if (!value) return false;
    out->push_back(*value);
  }
  return true;
}

std::optional<int64_t> ParseId(const std::string& text) {
  const auto value = ParseWholeNumber(text);
  if (!value) return std::nullopt;
  return static_cast<int64_t>(*value);
}

}  // namespace

DatasetParseResult ParsePoseLandmarkDataset(std::istream& text) {
  DatasetParseResult result;
  PoseLandmarkDataset dataset;
  std::unordered_set<int64_t> poses;
  std::string line;
  int line_number = 0;
  std::vector<double> numbers;
  const auto fail = [&](const std::string& why) {
    result.error = "line " + std::to_string(line_number) + ": " + why;
    return result;
  };
  while (std::getline(text, line)) {
    ++line_number;
    const std::vector<std::string> fields = Fields(line);
    if (fields.empty()) continue;
    const std::string& tag = fields[0];
    if (tag == "ODOMETRY") {
      if (fields.size() != 12) return fail("ODOMETRY takes 11 numbers");
      const auto from = ParseId(fields[1]);
      const auto to = ParseId(fields[2]);
      if (!from || !to) return fail("pose ids must be whole numbers");
      if (!ParseNumbers(fields, 3, &numbers)) return fail("a number is not finite");
      PoseLandmarkDataset::Odometry odometry;
      odometry.from = *from;
      odometry.to = *to;
      odometry.relative << numbers[0], numbers[1], numbers[2];
      odometry.covariance << numbers[3], numbers[4], numbers[5],  //
          numbers[4], numbers[6], numbers[7],                     //
          numbers[5], numbers[7], numbers[8];
      if (dataset.keyframes.empty()) {
        dataset.keyframes.push_back({*from, std::nullopt, {}});
        poses.insert(*from);
      }
      if (*from != dataset.keyframes.back().pose) {
        return fail("odometry from pose " + std::to_string(*from) + " does not continue the " +
                    "chain at pose " + std::to_string(dataset.keyframes.back().pose));
      }
      if (!poses.insert(*to).second) return fail("pose " + std::to_string(*to) + " seen before");
      dataset.keyframes.push_back({*to, static_cast<int>(dataset.odometry.size()), {}});
      dataset.odometry.push_back(odometry);
    } else if (tag == "LANDMARK") {
      if (fields.size() != 8) return fail("LANDMARK takes 7 numbers");
      const auto pose = ParseId(fields[1]);
      const auto landmark = ParseId(fields[2]);
      if (!pose || !landmark) return fail("ids must be whole numbers");
      if (!ParseNumbers(fields, 3, &numbers)) return fail("a number is not finite");
      if (dataset.keyframes.empty()) {
        dataset.keyframes.push_back({*pose, std::nullopt, {}});
        poses.insert(*pose);
      }
      if (*pose != dataset.keyframes.back().pose) {
        return fail("landmark seen from pose " + std::to_string(*pose) + ", not the latest (" +
                    std::to_string(dataset.keyframes.back().pose) + ")");
      }
      PoseLandmarkDataset::Observation observation;
      observation.pose = *pose;
      observation.landmark = *landmark;
      observation.position << numbers[0], numbers[1];
      observation.covariance << numbers[2], numbers[3], numbers[3], numbers[4];
      dataset.keyframes.back().observations.push_back(
          static_cast<int>(dataset.observations.size()));
      dataset.observations.push_back(observation);
    } else {
      return fail("unknown tag '" + tag + "' (ODOMETRY or LANDMARK)");
    }
  }
  if (dataset.keyframes.empty()) {
    result.error = "no ODOMETRY or LANDMARK line";
    return result;
  }
  result.dataset = std::move(dataset);
  return result;
}

namespace {

std::optional<Eigen::Matrix3d> Inverse3(const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d information = covariance.inverse();
  if (!information.allFinite()) return std::nullopt;
  return 0.5 * (information + information.transpose());
}

}  // namespace

std::optional<std::string> AddKeyframe(const PoseLandmarkDataset& dataset, size_t k,
                                       LandmarkReading reading, Smoother* smoother,
                                       double first_pose_sigma) {
  if (k >= dataset.keyframes.size()) return "keyframe " + std::to_string(k) + " is past the end";
  const PoseLandmarkDataset::Keyframe& keyframe = dataset.keyframes[k];
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  if (keyframe.odometry) {
    const PoseLandmarkDataset::Odometry& odometry = dataset.odometry[*keyframe.odometry];
    const auto previous = smoother->PoseEstimate(odometry.from);
    if (!previous) return "pose " + std::to_string(odometry.from) + " is not in the smoother";
    pose = ComposePoses(*previous, odometry.relative);
    if (auto error = smoother->AddPose(keyframe.pose, pose)) return error;
    const auto information = Inverse3(odometry.covariance);
    if (!information) return "odometry covariance is singular";
    if (auto error =
            smoother->AddOdometry(odometry.from, odometry.to, odometry.relative, *information)) {
      return error;
    }
  } else {
    if (auto error = smoother->AddPose(keyframe.pose, pose)) return error;
    const double information = 1.0 / (first_pose_sigma * first_pose_sigma);
    if (auto error = smoother->AddPosePrior(keyframe.pose, pose,
                                            information * Eigen::Matrix3d::Identity())) {
      return error;
    }
  }
  for (int index : keyframe.observations) {
    const PoseLandmarkDataset::Observation& observation = dataset.observations[index];
    const Eigen::Vector2d& local = observation.position;
    if (!smoother->LandmarkEstimate(observation.landmark)) {
      const Eigen::Vector3d at = ComposePoses(pose, Eigen::Vector3d(local(0), local(1), 0.0));
      if (auto error = smoother->AddLandmark(observation.landmark, at.head<2>())) return error;
    }
    std::optional<std::string> error;
    if (reading == LandmarkReading::kBearingRange) {
      const double c11 = observation.covariance(0, 0);
      const double c22 = observation.covariance(1, 1);
      // load2D's rule (see the header).
      const bool uniform = std::abs(c11 - c22) < 1e-4;
      const double range_sigma = uniform ? std::sqrt(c11) : 1.0;
      const double bearing_sigma = uniform ? std::sqrt(c11 / 10.0) : 1.0;
      Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
      information(0, 0) = 1.0 / (range_sigma * range_sigma);
      information(1, 1) = 1.0 / (bearing_sigma * bearing_sigma);
      error = smoother->AddRangeBearing(
          observation.pose, observation.landmark,
          Eigen::Vector2d(local.norm(), std::atan2(local(1), local(0))), information);
    } else {
      const Eigen::Matrix2d information = observation.covariance.inverse();
      error = smoother->AddRelativePosition(observation.pose, observation.landmark, local,
                                            0.5 * (information + information.transpose()));
    }
    if (error) return error;
  }
  return std::nullopt;
}

}  // namespace slammtt
