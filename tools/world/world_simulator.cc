#include "tools/world/world_simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/world/portable_random.h"
#include "tools/world/scattered_landmarks.h"

namespace slammtt {

namespace {

// Random streams of one simulation (DeriveSeed's `stream` argument).
constexpr uint64_t kOdometryStream = 1;
constexpr uint64_t kLaserStream = 2;
constexpr uint64_t kFeatureStream = 3;
constexpr uint64_t kMoverStreams = 4;  // DeriveSeed(DeriveSeed(seed, 4), object id)
constexpr uint64_t kArtefactStream = 5;
constexpr uint64_t kBeamAngleStream = 6;
constexpr uint64_t kGaitStreams = 7;   // DeriveSeed(DeriveSeed(seed, 7), person id)

int64_t EventTimeUs(int64_t index, double rate_hz) {
  return std::llround(static_cast<double>(index) * 1e6 / rate_hz);
}

}  // namespace

void CountBeamsIntoTruth(const std::vector<SimulatedBeam>& beams, TruthSnapshot* truth) {
  const int num_objects = static_cast<int>(truth->objects.size());
  const std::vector<int> counts = CountBeamsPerObject(beams, num_objects);
  for (const SimulatedBeam& beam : beams) {
    if (beam.valid && beam.segment >= 0) {
      ++truth->segments[static_cast<size_t>(beam.segment)].beams_on_segment;
    }
  }
  for (int i = 0; i < num_objects; ++i) {
    ObjectTruth& object = truth->objects[static_cast<size_t>(i)];
    object.beams_on_object = counts[static_cast<size_t>(i)];
    if (object.kind == ObjectKind::kPerson) {
      object.beams_on_object =
          counts[static_cast<size_t>(i) + 1] + counts[static_cast<size_t>(i) + 2];
    }
    object.visible = object.beams_on_object >= 1;
  }
}

namespace {

// std::invalid_argument listing every problem of `scenario`, if it has any.
void RefuseProblems(const Scenario& scenario) {
  const std::vector<std::string> problems = FindScenarioProblems(scenario);
  if (!problems.empty()) {
    std::string text = "invalid scenario";
    for (const std::string& line : problems) text += (text.size() > 16 ? "; " : ": ") + line;
    throw std::invalid_argument(text);
  }
}

// The scenario as simulated: checked, then its scattered landmarks drawn from the seed.
Scenario Simulated(const Scenario& scenario, uint64_t seed) {
  RefuseProblems(scenario);
  return WithScatteredLandmarks(scenario, seed);
}

}  // namespace

WorldSimulator::WorldSimulator(const Scenario& scenario, uint64_t seed, SensorOutput output)
    : scenario_(Simulated(scenario, seed)),
      output_(output),
      beam_sequence_(scenario.laser),
      odometry_(scenario.odometry) {
  RefuseProblems(scenario_);  // the drawn landmarks' ids against the movers'
  duration_us_ = std::llround(scenario_.duration_s * 1e6);
  beam_angles_rad_ = LaserBeamAngles(scenario_.laser);
  const uint64_t mover_seed = DeriveSeed(seed, kMoverStreams);
  const uint64_t gait_seed = DeriveSeed(seed, kGaitStreams);
  const GaitSpec gait = GaitFromLegs(scenario_.legs);
  for (const MoverSpec& mover : scenario_.movers) {
    std::mt19937_64 rng(DeriveSeed(mover_seed, static_cast<uint64_t>(mover.id)));
    mover_paths_.push_back(BuildMoverPath(mover, scenario_.duration_s, rng));
    gaits_.emplace_back();
    if (BodyOf(scenario_, mover) == MoverBody::kLegs) {
      std::mt19937_64 sway(DeriveSeed(gait_seed, static_cast<uint64_t>(mover.id)));
      gaits_.back().emplace(gait, UniformBetween(sway, 0.0, 2.0 * M_PI));
    }
  }
  static_geometry_ = BuildStaticGeometry(scenario_.statics);
  for (const StaticSegment& s : static_geometry_.segments) {
    segments_.push_back(s.segment);
    artefact_inputs_.segment_dropout_probability.push_back(
        scenario_.statics[static_cast<size_t>(s.spec)].dropout_probability);
  }
  for (const StaticCircle& c : static_geometry_.circles) {
    artefact_inputs_.circle_dropout_probability.push_back(
        scenario_.statics[static_cast<size_t>(c.spec)].dropout_probability);
  }
  artefact_rng_.seed(DeriveSeed(seed, kArtefactStream));
  beam_angle_rng_.seed(DeriveSeed(seed, kBeamAngleStream));
  driver_ = RobotDriver(scenario_.robot);
  odometry_rng_.seed(DeriveSeed(seed, kOdometryStream));
  laser_rng_.seed(DeriveSeed(seed, kLaserStream));
  feature_rng_.seed(DeriveSeed(seed, kFeatureStream));
  robot_.pose = scenario_.robot.start;
  robot_.pose.heading_rad = WrapAngle(robot_.pose.heading_rad);
  robot_.sensor_pose =
      SensorPoseFromRobot(robot_.pose, scenario_.laser.mount_a_m, scenario_.laser.mount_b_m,
                          scenario_.laser.mount_yaw_deg * M_PI / 180.0);
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
      SensorPoseFromRobot(robot_.pose, scenario_.laser.mount_a_m, scenario_.laser.mount_b_m,
                          scenario_.laser.mount_yaw_deg * M_PI / 180.0);
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

TruthSnapshot WorldSimulator::TruthAt(int64_t time_us, std::vector<Circle>* circles,
                                      std::vector<int>* circle_object) {
  TruthSnapshot truth;
  truth.time_us = time_us;
  truth.robot = robot_;
  circles->clear();
  circle_object->clear();
  auto add = [&](const ObjectTruth& object, bool has_surface) {
    if (has_surface) {
      circles->push_back(Circle{object.x_m, object.y_m, object.radius_m});
      circle_object->push_back(static_cast<int>(truth.objects.size()));
    }
    truth.objects.push_back(object);
  };
  for (const StaticCircle& s : static_geometry_.circles) {
    ObjectTruth object;
    object.id = s.id;
    object.is_static = true;
    object.kind = s.kind;
    object.x_m = s.circle.x_m;
    object.y_m = s.circle.y_m;
    object.radius_m = s.circle.radius_m;
    add(object, true);
  }
  for (const StaticSegment& s : static_geometry_.segments) {
    truth.segments.push_back(SegmentTruth{s.id, s.kind, s.segment, 0});
  }
  const double t_s = static_cast<double>(time_us) * 1e-6;
  for (size_t i = 0; i < scenario_.movers.size(); ++i) {
    std::optional<PersonGait>& gait = gaits_[i];
    if (!mover_paths_[i].ExistsAt(t_s)) {
      if (gait) gait->Reset();
      continue;
    }
    const MoverState state = mover_paths_[i].StateAt(t_s);
    ObjectTruth object;
    object.id = scenario_.movers[i].id;
    object.x_m = state.x_m;
    object.y_m = state.y_m;
    object.vx_mps = state.vx_mps;
    object.vy_mps = state.vy_mps;
    if (!gait) {
      object.kind = ObjectKind::kDisc;
      object.radius_m = scenario_.movers[i].radius_m;
      add(object, true);
      continue;
    }
    gait->Update(t_s, state);
    const std::array<LegState, 2>& legs = gait->legs();
    const double leg_radius = scenario_.legs.radius_m;
    object.kind = ObjectKind::kPerson;
    object.radius_m =
        0.5 * std::hypot(legs[0].x_m - legs[1].x_m, legs[0].y_m - legs[1].y_m) + leg_radius;
    add(object, false);
    for (int k = 0; k < 2; ++k) {
      const LegState& leg = legs[static_cast<size_t>(k)];
      ObjectTruth leg_truth;
      leg_truth.id = LegId(object.id, k);
      leg_truth.kind = ObjectKind::kLeg;
      leg_truth.parent_id = object.id;
      leg_truth.x_m = leg.x_m;
      leg_truth.y_m = leg.y_m;
      leg_truth.vx_mps = leg.vx_mps;
      leg_truth.vy_mps = leg.vy_mps;
      leg_truth.radius_m = leg_radius;
      add(leg_truth, true);
    }
  }
  return truth;
}

WorldScene WorldSimulator::SceneAt(int64_t time_us, const RobotTruth& robot) {
  WorldScene scene;
  scene.truth = TruthAt(time_us, &scene.circles, &scene.circle_object);
  scene.truth.robot = robot;
  return scene;
}

std::vector<FeatureTarget> WorldSimulator::FeatureTargets(
    const TruthSnapshot& truth, const std::vector<int>& circle_object) const {
  // Objects with a circle give a feature of their own, except legs: their person gives one.
  std::vector<int> first_circle(truth.objects.size(), -1);
  for (size_t c = 0; c < circle_object.size(); ++c) {
    first_circle[static_cast<size_t>(circle_object[c])] = static_cast<int>(c);
  }
  std::vector<FeatureTarget> targets(truth.objects.size());
  for (size_t i = 0; i < truth.objects.size(); ++i) {
    const ObjectTruth& o = truth.objects[i];
    FeatureTarget& target = targets[i];
    target.x_m = o.x_m;
    target.y_m = o.y_m;
    target.width_m = 2.0 * o.radius_m;
    target.beams_on_target = o.beams_on_object;
    if (o.kind == ObjectKind::kPerson) {
      target.first_circle = first_circle[i + 1];  // its two legs follow it
      target.num_circles = 2;
    } else if (o.kind == ObjectKind::kLeg) {
      target.beams_on_target = -1;  // no feature of its own (see MakeSensorFrame)
    } else {
      target.first_circle = first_circle[i];
      target.num_circles = 1;
    }
  }
  return targets;
}

SensorFrame WorldSimulator::MakeSensorFrame(int64_t time_us) {
  SensorFrame frame;
  frame.time_us = time_us;
  frame.sequence = next_scan_index_;
  std::vector<Circle> circles;
  std::vector<int> circle_object;
  frame.truth = TruthAt(time_us, &circles, &circle_object);
  const LaserSpec& laser = scenario_.laser;

  // The laser is always ray-cast (and its noise always drawn), whatever the output: ground truth
  // needs the beam counts, and the scans of "both" equal those of "scans".
  const std::vector<double> angles = beam_sequence_.Next(beam_angle_rng_);
  const std::vector<BeamHit> hits =
      CastBeams(robot_.sensor_pose, angles, circles, segments_, laser.max_range_m);
  ArtefactInputs& artefacts = artefact_inputs_;
  if (NeedsFootprintEdges(laser)) {
    const double half_rad = 0.5 * laser.artefacts.beam_divergence_deg * M_PI / 180.0;
    std::vector<double> edge(angles.size());
    for (size_t i = 0; i < angles.size(); ++i) edge[i] = angles[i] - half_rad;
    artefacts.lower_edge_hits =
        CastBeams(robot_.sensor_pose, edge, circles, segments_, laser.max_range_m);
    for (size_t i = 0; i < angles.size(); ++i) edge[i] = angles[i] + half_rad;
    artefacts.upper_edge_hits =
        CastBeams(robot_.sensor_pose, edge, circles, segments_, laser.max_range_m);
  }
  std::vector<SimulatedBeam> beams =
      MeasureScan(laser, angles, hits, artefacts, laser_rng_, artefact_rng_);
  for (SimulatedBeam& beam : beams) {
    if (beam.object >= 0) beam.object = circle_object[static_cast<size_t>(beam.object)];
  }
  CountBeamsIntoTruth(beams, &frame.truth);
  if (output_ != SensorOutput::kFeatures) {
    frame.has_scan = true;
    frame.scan = std::move(beams);
  }
  if (output_ != SensorOutput::kScans) {
    // Legs give no feature of their own: they are left out of the targets, and a leg is
    // "visible" when its person's feature was emitted and the leg had a beam or a clear sight.
    std::vector<FeatureTarget> targets = FeatureTargets(frame.truth, circle_object);
    std::vector<int> target_object;
    std::vector<FeatureTarget> emitted;
    for (size_t i = 0; i < targets.size(); ++i) {
      if (targets[i].beams_on_target < 0) continue;
      target_object.push_back(static_cast<int>(i));
      emitted.push_back(targets[i]);
    }
    std::vector<bool> visible;
    frame.has_features = true;
    frame.features = EmitPointFeatures(robot_.sensor_pose, emitted, circles, segments_, laser,
                                       scenario_.features, feature_rng_, &visible);
    for (PointFeature& f : frame.features) f.object = target_object[static_cast<size_t>(f.object)];
    for (size_t k = 0; k < emitted.size(); ++k) {
      const size_t i = static_cast<size_t>(target_object[k]);
      frame.truth.objects[i].visible = visible[k];
      if (frame.truth.objects[i].kind == ObjectKind::kPerson) {
        for (size_t leg = i + 1; leg <= i + 2; ++leg) {
          frame.truth.objects[leg].visible =
              visible[k] && frame.truth.objects[leg].beams_on_object >= 1;
        }
      }
    }
  }
  return frame;
}

}  // namespace slammtt
