#include "tools/legs/simulated_recording.h"

#include <cmath>
#include <stdexcept>

#include "tools/world/world_messages.h"
#include "tools/world/world_simulator.h"

namespace slammtt {

Recording SimulateRecording(const std::string& name, const Scenario& scenario, uint64_t seed,
                            int every) {
  if (every < 1) throw std::invalid_argument("simulated recording: every must be at least 1");
  Recording recording;
  recording.name = name;
  WorldSimulator world(scenario, seed, SensorOutput::kScans);
  int64_t frames = 0;
  while (!world.Done()) {
    const WorldEvent event = world.Next();
    if (event.kind != WorldEvent::Kind::kSensor || !event.sensor.has_scan) continue;
    if (frames++ % every != 0) continue;
    const SensorFrame& frame = event.sensor;
    const slammtt_msgs::laser_scan_t msg = ToLaserScanMessage(frame, scenario.laser, 0);
    RecordedScan scan;
    scan.utime = msg.utime;
    scan.angle_rad = msg.angle_rad;
    scan.range_m = msg.range_m;
    scan.valid.assign(msg.valid.begin(), msg.valid.end());
    scan.range_min_m = msg.range_min_m;
    scan.range_max_m = msg.range_max_m;
    scan.labelled = true;
    const Pose2D& sensor = frame.truth.robot.sensor_pose;
    const double c = std::cos(sensor.heading_rad);
    const double s = std::sin(sensor.heading_rad);
    for (const ObjectTruth& o : frame.truth.objects) {
      if (o.kind != ObjectKind::kLeg && o.kind != ObjectKind::kPerson) continue;
      const double dx = o.x_m - sensor.x_m;
      const double dy = o.y_m - sensor.y_m;
      const Eigen::Vector2d in_sensor(c * dx + s * dy, -s * dx + c * dy);
      scan.people_m.push_back(in_sensor);
      if (o.kind == ObjectKind::kLeg && o.beams_on_object >= 1) scan.labels_m.push_back(in_sensor);
    }
    recording.scans.push_back(std::move(scan));
  }
  if (recording.scans.empty()) {
    throw std::invalid_argument("simulated recording " + name + ": the scenario gives no scans");
  }
  return recording;
}

}  // namespace slammtt
