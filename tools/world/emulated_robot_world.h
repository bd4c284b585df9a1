// The synthetic world of one robot whose motion comes from outside: the emulated P3-DX base
// integrates the velocities it is commanded into its encoder pose, and this world turns that
// into the robot's true pose (SlippingBase: the scenario's wheel slip), moves the scenario's
// people and discs (WorldSimulator::SceneAt), answers the emulated laser's beams by ray casting
// from the sensor's true pose (the scenario's laser mount), and gives the ground truth at any
// recent moment. drivers/sim_robot serves it behind the two device emulators.
//
// Time: microseconds of the caller's clock, non-decreasing across Advance calls. The world
// keeps the scenes of the last `history_us` to answer beams and truth for moments between two
// steps (the robot's pose is interpolated; people and discs are those of the step at or before
// the moment). Pure: no clock, no I/O, randomness from the seed (the scenario's people and the
// wheel slip); the same Advance calls give the same world.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "tools/world/slipping_base.h"
#include "tools/world/world_simulator.h"

namespace slammtt {

// The first surface along a beam.
struct BeamSurface {
  double range_m = 0.0;
  // The scenario's dropout_probability of the surface; 1 beyond the laser's grazing angle.
  double dropout_probability = 0.0;
};

class EmulatedRobotWorld {
 public:
  // std::invalid_argument for a scenario WorldSimulator refuses, or history_us <= 0.
  EmulatedRobotWorld(const Scenario& scenario, uint64_t seed, int64_t history_us = 3000000);

  // The base's encoders read `encoder_pose` (its odometry frame) at time_us. The first call
  // puts the robot at the scenario's start pose; an earlier time than the last is ignored.
  void Advance(int64_t time_us, const Pose2D& encoder_pose);

  // The first surface along `sensor_angle_rad` (sensor frame, CCW) at time_us, within the
  // laser's max_range_m; nullopt when there is none (or before the first Advance). A time
  // after the last step is answered with the last step's world.
  std::optional<BeamSurface> CastBeam(double sensor_angle_rad, int64_t time_us) const;

  // Ground truth at time_us (time_us of the snapshot; robot pose interpolated between steps),
  // with the beam counts of a noise-free scan along `beam_angles_rad` (sensor frame) from the
  // sensor's pose at that moment: a beam counts when it hits a surface within [min_range_m,
  // max_range_m] whose dropout probability is below 0.5. nullopt when time_us is outside the
  // kept history (older than history_us before the last step, or later than the last step).
  std::optional<TruthSnapshot> TruthAt(int64_t time_us,
                                       const std::vector<double>& beam_angles_rad) const;

  // The robot at the last step.
  const RobotTruth& robot() const;
  const Scenario& scenario() const { return world_.scenario(); }

 private:
  struct Step {
    int64_t time_us = 0;
    WorldScene scene;
  };
  // Index of the step at or before time_us (0 for earlier times); history_ not empty.
  size_t StepIndexAt(int64_t time_us) const;
  RobotTruth RobotAt(int64_t time_us) const;
  RobotTruth MakeRobotTruth(const Pose2D& pose, double linear_mps, double angular_radps) const;
  double DropoutProbability(const BeamHit& hit) const;

  WorldSimulator world_;
  uint64_t slip_seed_ = 0;
  std::optional<SlippingBase> base_;  // from the first Advance on
  RobotTruth start_robot_;
  int64_t history_us_ = 0;
  std::deque<Step> history_;
  double grazing_cos_ = 0.0;  // cos(grazing_dropout_deg)
};

}  // namespace slammtt
