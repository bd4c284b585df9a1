#include "tools/world/emulated_robot_world.h"

#include <cmath>
#include <stdexcept>

#include "tools/world/portable_random.h"

namespace slammtt {

namespace {

// Random stream of the wheel slip (WorldSimulator uses 1 to 7).
constexpr uint64_t kSlipStream = 8;

}  // namespace

EmulatedRobotWorld::EmulatedRobotWorld(const Scenario& scenario, uint64_t seed,
                                       int64_t history_us)
    : world_(scenario, seed, SensorOutput::kScans),
      slip_seed_(DeriveSeed(seed, kSlipStream)),
      history_us_(history_us),
      grazing_cos_(std::cos(scenario.laser.artefacts.grazing_dropout_deg * M_PI / 180.0)) {
  if (history_us <= 0) throw std::invalid_argument("EmulatedRobotWorld: history_us must be > 0");
  Pose2D start = scenario.robot.start;
  start.heading_rad = WrapAngle(start.heading_rad);
  start_robot_ = MakeRobotTruth(start, 0.0, 0.0);
}

RobotTruth EmulatedRobotWorld::MakeRobotTruth(const Pose2D& pose, double linear_mps,
                                              double angular_radps) const {
  const LaserSpec& laser = world_.scenario().laser;
  RobotTruth robot;
  robot.pose = pose;
  robot.sensor_pose = SensorPoseFromRobot(pose, laser.mount_a_m, laser.mount_b_m,
                                          laser.mount_yaw_deg * M_PI / 180.0);
  robot.linear_mps = linear_mps;
  robot.angular_radps = angular_radps;
  return robot;
}

void EmulatedRobotWorld::Advance(int64_t time_us, const Pose2D& encoder_pose) {
  if (!base_) {
    // The encoders' pose at the first call is where the robot starts.
    base_.emplace(start_robot_.pose, encoder_pose, world_.scenario().odometry, slip_seed_);
  }
  if (!history_.empty() && time_us < history_.back().time_us) return;
  base_->Advance(time_us, encoder_pose);
  const RobotTruth robot =
      MakeRobotTruth(base_->pose(), base_->linear_mps(), base_->angular_radps());
  if (!history_.empty() && history_.back().time_us == time_us) {
    history_.back().scene.truth.robot = robot;
    return;
  }
  history_.push_back(Step{time_us, world_.SceneAt(time_us, robot)});
  while (history_.size() > 2 && history_.front().time_us < time_us - history_us_) {
    history_.pop_front();
  }
}

size_t EmulatedRobotWorld::StepIndexAt(int64_t time_us) const {
  // Steps are in time order: the last one at or before time_us.
  for (size_t i = history_.size(); i > 0; --i) {
    if (history_[i - 1].time_us <= time_us) return i - 1;
  }
  return 0;
}

RobotTruth EmulatedRobotWorld::RobotAt(int64_t time_us) const {
  const size_t i = StepIndexAt(time_us);
  const Step& before = history_[i];
  const RobotTruth& a = before.scene.truth.robot;
  if (time_us <= before.time_us || i + 1 == history_.size()) return a;
  const Step& after = history_[i + 1];
  const RobotTruth& b = after.scene.truth.robot;
  const double f = static_cast<double>(time_us - before.time_us) /
                   static_cast<double>(after.time_us - before.time_us);
  Pose2D pose;
  pose.x_m = a.pose.x_m + f * (b.pose.x_m - a.pose.x_m);
  pose.y_m = a.pose.y_m + f * (b.pose.y_m - a.pose.y_m);
  pose.heading_rad =
      WrapAngle(a.pose.heading_rad + f * WrapAngle(b.pose.heading_rad - a.pose.heading_rad));
  return MakeRobotTruth(pose, b.linear_mps, b.angular_radps);
}

double EmulatedRobotWorld::DropoutProbability(const BeamHit& hit) const {
  if (hit.incidence_cos < grazing_cos_) return 1.0;
  const ArtefactInputs& dropouts = world_.surface_dropouts();
  if (hit.segment >= 0) {
    return dropouts.segment_dropout_probability[static_cast<size_t>(hit.segment)];
  }
  const size_t circle = static_cast<size_t>(hit.circle);
  // Static circles come first in the scene; people and discs always return.
  return circle < dropouts.circle_dropout_probability.size()
             ? dropouts.circle_dropout_probability[circle]
             : 0.0;
}

std::optional<BeamSurface> EmulatedRobotWorld::CastBeam(double sensor_angle_rad,
                                                        int64_t time_us) const {
  if (history_.empty()) return std::nullopt;
  const WorldScene& scene = history_[StepIndexAt(time_us)].scene;
  const Pose2D sensor = RobotAt(time_us).sensor_pose;
  const BeamHit hit = CastRay(sensor.x_m, sensor.y_m, sensor.heading_rad + sensor_angle_rad,
                              scene.circles, world_.segments());
  if (!hit.hit() || hit.range_m > world_.scenario().laser.max_range_m) return std::nullopt;
  return BeamSurface{hit.range_m, DropoutProbability(hit)};
}

std::optional<TruthSnapshot> EmulatedRobotWorld::TruthAt(
    int64_t time_us, const std::vector<double>& beam_angles_rad) const {
  if (history_.empty() || time_us > history_.back().time_us ||
      time_us < history_.front().time_us) {
    return std::nullopt;
  }
  const WorldScene& scene = history_[StepIndexAt(time_us)].scene;
  TruthSnapshot truth = scene.truth;
  truth.time_us = time_us;
  truth.robot = RobotAt(time_us);
  const LaserSpec& laser = world_.scenario().laser;
  const std::vector<BeamHit> hits = CastBeams(truth.robot.sensor_pose, beam_angles_rad,
                                              scene.circles, world_.segments(), laser.max_range_m);
  std::vector<SimulatedBeam> beams(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    const BeamHit& hit = hits[i];
    SimulatedBeam& beam = beams[i];
    beam.angle_rad = beam_angles_rad[i];
    if (!hit.hit()) continue;
    beam.true_range_m = hit.range_m;
    beam.range_m = hit.range_m;
    beam.valid = hit.range_m >= laser.min_range_m && DropoutProbability(hit) < 0.5;
    beam.object = hit.circle >= 0 ? scene.circle_object[static_cast<size_t>(hit.circle)] : -1;
    beam.segment = hit.segment;
  }
  CountBeamsIntoTruth(beams, &truth);
  return truth;
}

const RobotTruth& EmulatedRobotWorld::robot() const {
  return history_.empty() ? start_robot_ : history_.back().scene.truth.robot;
}

}  // namespace slammtt
