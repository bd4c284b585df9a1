#include "tools/world/world_simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/world/portable_random.h"

namespace slammtt {

namespace {

// Random streams of one simulation (DeriveSeed's `stream` argument).
constexpr uint64_t kOdometryStream = 1;
constexpr uint64_t kLaserStream = 2;
constexpr uint64_t kFeatureStream = 3;
constexpr uint64_t kMoverStreams = 4;  // DeriveSeed(DeriveSeed(seed, 4), object id)

int64_t EventTimeUs(int64_t index, double rate_hz) {
  return std::llround(static_cast<double>(index) * 1e6 / rate_hz);
}

}  // namespace

WorldSimulator::WorldSimulator(const Scenario& scenario, uint64_t seed, SensorOutput output)
    : scenario_(scenario), output_(output), odometry_(scenario.odometry) {
  const std::vector<std::string> problems = FindScenarioProblems(scenario_);
  if (!problems.empty()) {
    std::string text = "invalid scenario";
    for (const std::string& line : problems) text += (text.size() > 16 ? "; " : ": ") + line;
    throw std::invalid_argument(text);
  }
  duration_us_ = std::llround(scenario_.duration_s * 1e6);
  beam_angles_rad_ = LaserBeamAngles(scenario_.laser);
  const uint64_t mover_seed = DeriveSeed(seed, kMoverStreams);
  for (const MoverSpec& mover : scenario_.movers) {
    std::mt19937_64 rng(DeriveSeed(mover_seed, static_cast<uint64_t>(mover.id)));
    mover_paths_.push_back(BuildMoverPath(mover, scenario_.duration_s, rng));
  }
  driver_ = RobotDriver(scenario_.robot);
  odometry_rng_.seed(DeriveSeed(seed, kOdometryStream));
  laser_rng_.seed(DeriveSeed(seed, kLaserStream));
  feature_rng_.seed(DeriveSeed(seed, kFeatureStream));
  robot_.pose = scenario_.robot.start;
  robot_.pose.heading_rad = WrapAngle(robot_.pose.heading_rad);
  robot_.sensor_pose =
      SensorPoseFromRobot(robot_.pose, scenario_.laser.mount_a_m, scenario_.laser.mount_b_m);
}

bool WorldSimulator::Done() const {
  return EventTimeUs(next_odometry_index_, scenario_.odometry.rate_hz) > duration_us_ &&
         EventTimeUs(next_scan_index_, scenario_.laser.rate_hz) > duration_us_;
}

int64_t WorldSimulator::NextEventTimeUs() const {
  const int64_t odometry_us = EventTimeUs(next_odometry_index_, scenario_.odometry.rate_hz);
  const int64_t scan_us = EventTimeUs(next_scan_index_, scenario_.laser.rate_hz);
  return odometry_us <= duration_us_ ? std::min(odometry_us, scan_us) : scan_us;
}

void WorldSimulator::SetCommandOverride(const std::optional<VelocityCommand>& command) {
  command_override_ = command;
  if (command_override_) {
    command_override_->linear_mps =
        std::clamp(command_override_->linear_mps, -kMaxRobotSpeedMps, kMaxRobotSpeedMps);
  }
}

void WorldSimulator::AdvanceRobotTo(int64_t time_us) {
  auto control_tick = [&] {
    if (robot_time_us_ != next_control_us_) return;
    command_ =
        command_override_ ? *command_override_ : driver_.CommandAt(robot_time_us_, robot_.pose);
    next_control_us_ += kRobotControlPeriodUs;
  };
  while (robot_time_us_ < time_us) {
    control_tick();
    const int64_t step_end_us = std::min(time_us, next_control_us_);
    const double dt_s = static_cast<double>(step_end_us - robot_time_us_) * 1e-6;
    robot_.pose = MoveUnicycle(robot_.pose, command_.linear_mps, command_.angular_radps, dt_s);
    distance_since_odometry_m_ += command_.linear_mps * dt_s;
    rotation_since_odometry_rad_ += command_.angular_radps * dt_s;
    robot_time_us_ = step_end_us;
  }
  control_tick();  // the command in force at time_us (its velocity is part of the truth)
  robot_.linear_mps = command_.linear_mps;
  robot_.angular_radps = command_.angular_radps;
  robot_.sensor_pose =
      SensorPoseFromRobot(robot_.pose, scenario_.laser.mount_a_m, scenario_.laser.mount_b_m);
}

WorldEvent WorldSimulator::Next() {
  if (Done()) throw std::logic_error("WorldSimulator::Next called after the end");
  const int64_t odometry_us = EventTimeUs(next_odometry_index_, scenario_.odometry.rate_hz);
  const int64_t scan_us = EventTimeUs(next_scan_index_, scenario_.laser.rate_hz);
  WorldEvent event;
  if (odometry_us <= duration_us_ && odometry_us <= scan_us) {
    AdvanceRobotTo(odometry_us);
    event.kind = WorldEvent::Kind::kOdometry;
    event.time_us = odometry_us;
    if (next_odometry_index_ == 0) {
      event.odometry = odometry_.Start(odometry_us);
    } else {
      event.odometry = odometry_.Update(odometry_us, distance_since_odometry_m_,
                                        rotation_since_odometry_rad_, odometry_rng_);
    }
    distance_since_odometry_m_ = 0.0;
    rotation_since_odometry_rad_ = 0.0;
    ++next_odometry_index_;
    return event;
  }
  AdvanceRobotTo(scan_us);
  event.kind = WorldEvent::Kind::kSensor;
  event.time_us = scan_us;
  event.sensor = MakeSensorFrame(scan_us);
  ++next_scan_index_;
  return event;
}

TruthSnapshot WorldSimulator::TruthAt(int64_t time_us, std::vector<Circle>* circles) const {
  TruthSnapshot truth;
  truth.time_us = time_us;
  truth.robot = robot_;
  circles->clear();
  for (const StaticObjectSpec& s : scenario_.statics) {
    ObjectTruth object;
    object.id = s.id;
    object.is_static = true;
    object.x_m = s.x_m;
    object.y_m = s.y_m;
    object.radius_m = s.radius_m;
    truth.objects.push_back(object);
    circles->push_back(Circle{s.x_m, s.y_m, s.radius_m});
  }
  const double t_s = static_cast<double>(time_us) * 1e-6;
  for (size_t i = 0; i < scenario_.movers.size(); ++i) {
    if (!mover_paths_[i].ExistsAt(t_s)) continue;
    const MoverState state = mover_paths_[i].StateAt(t_s);
    ObjectTruth object;
    object.id = scenario_.movers[i].id;
    object.x_m = state.x_m;
    object.y_m = state.y_m;
    object.vx_mps = state.vx_mps;
    object.vy_mps = state.vy_mps;
    object.radius_m = scenario_.movers[i].radius_m;
    truth.objects.push_back(object);
    circles->push_back(Circle{state.x_m, state.y_m, object.radius_m});
  }
  return truth;
}

SensorFrame WorldSimulator::MakeSensorFrame(int64_t time_us) {
  SensorFrame frame;
  frame.time_us = time_us;
  frame.sequence = next_scan_index_;
  std::vector<Circle> circles;
  frame.truth = TruthAt(time_us, &circles);
  const int num_objects = static_cast<int>(circles.size());

  // The laser is always ray-cast (and its noise always drawn), whatever the output: ground truth
  // needs the beam counts, and the scans of "both" equal those of "scans".
  const std::vector<BeamHit> hits =
      CastBeams(robot_.sensor_pose, beam_angles_rad_, circles, scenario_.laser.max_range_m);
  std::vector<SimulatedBeam> beams =
      MeasureScan(scenario_.laser, beam_angles_rad_, hits, laser_rng_);
  const std::vector<int> counts = CountBeamsPerObject(beams, num_objects);
  for (int i = 0; i < num_objects; ++i) {
    frame.truth.objects[static_cast<size_t>(i)].beams_on_object = counts[static_cast<size_t>(i)];
    frame.truth.objects[static_cast<size_t>(i)].visible = counts[static_cast<size_t>(i)] >= 1;
  }
  if (output_ != SensorOutput::kFeatures) {
    frame.has_scan = true;
    frame.scan = std::move(beams);
  }
  if (output_ != SensorOutput::kScans) {
    std::vector<bool> visible;
    frame.has_features = true;
    frame.features = EmitPointFeatures(robot_.sensor_pose, circles, counts, scenario_.laser,
                                       scenario_.features, feature_rng_, &visible);
    for (int i = 0; i < num_objects; ++i) {
      frame.truth.objects[static_cast<size_t>(i)].visible = visible[static_cast<size_t>(i)];
    }
  }
  return frame;
}

}  // namespace slammtt
