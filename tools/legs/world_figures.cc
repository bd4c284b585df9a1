#include "tools/legs/world_figures.h"

#include <cmath>
#include <stdexcept>

#include "perception/segmenter.h"
#include "tools/legs/leg_dataset.h"
#include "tools/world/world_messages.h"
#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

Eigen::Vector2d Cartesian(double range_m, double bearing_rad) {
  return range_m * Eigen::Vector2d(std::cos(bearing_rad), std::sin(bearing_rad));
}

// A point of the world frame in the sensor frame of `sensor`.
struct SensorFrameOf {
  explicit SensorFrameOf(const Pose2D& sensor)
      : x(sensor.x_m), y(sensor.y_m), c(std::cos(sensor.heading_rad)),
        s(std::sin(sensor.heading_rad)) {}
  Eigen::Vector2d operator()(double wx, double wy) const {
    const double dx = wx - x;
    const double dy = wy - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
  double x, y, c, s;
};

// People with the beams of their most visible leg, and the static surfaces, in the sensor
// frame.
void TruthInSensorFrame(const TruthSnapshot& truth, std::vector<TruthPerson>* people,
                        std::vector<TruthSegment>* segments) {
  const SensorFrameOf to_sensor(truth.robot.sensor_pose);
  people->clear();
  segments->clear();
  for (const ObjectTruth& o : truth.objects) {
    if (o.kind != ObjectKind::kPerson) continue;
    TruthPerson person;
    person.centre_m = to_sensor(o.x_m, o.y_m);
    for (const ObjectTruth& leg : truth.objects) {
      if (leg.kind == ObjectKind::kLeg && leg.parent_id == o.id) {
        person.max_leg_beams = std::max(person.max_leg_beams, leg.beams_on_object);
      }
    }
    people->push_back(person);
  }
  for (const SegmentTruth& s : truth.segments) {
    TruthSegment t;
    t.first_m = to_sensor(s.segment.x0_m, s.segment.y0_m);
    t.second_m = to_sensor(s.segment.x1_m, s.segment.y1_m);
    t.wall = s.kind == ObjectKind::kWall;
    segments->push_back(t);
  }
}

}  // namespace

WorldFigures MeasureWorldFigures(const Scenario& scenario, const std::vector<uint64_t>& seeds,
                                 const SegmenterOptions& options, int every,
                                 const FeatureScoreOptions& score) {
  if (every < 1) throw std::invalid_argument("world figures: every must be at least 1");
  WorldFigures figures;
  Segmenter segmenter(options);
  std::vector<TruthPerson> people;
  std::vector<TruthSegment> segments;
  std::vector<Eigen::Vector2d> person_points, point_features;
  std::vector<LineObservation> lines;
  for (uint64_t seed : seeds) {
    WorldSimulator world(scenario, seed, SensorOutput::kScans);
    FeatureScore seed_score;
    int64_t frames = 0;
    while (!world.Done()) {
      const WorldEvent event = world.Next();
      if (event.kind != WorldEvent::Kind::kSensor || !event.sensor.has_scan) continue;
      if (frames++ % every != 0) continue;
      const slammtt_msgs::laser_scan_t msg = ToLaserScanMessage(event.sensor, scenario.laser, 0);
      RecordedScan scan;
      scan.angle_rad = msg.angle_rad;
      scan.range_m = msg.range_m;
      scan.valid.assign(msg.valid.begin(), msg.valid.end());
      scan.range_min_m = msg.range_min_m;
      scan.range_max_m = msg.range_max_m;
      const std::vector<Feature>& features = segmenter.Segment(scan.view());
      person_points.clear();
      for (const PersonFeature& p : segmenter.people()) {
        person_points.push_back(Cartesian(p.range_m, p.bearing_rad));
      }
      point_features.clear();
      for (const Feature& f : features) {
        point_features.push_back(Cartesian(f.range_m, f.bearing_rad));
      }
      lines.clear();
      for (const LineFeature& l : segmenter.lines()) {
        lines.push_back({l.rho_m, l.alpha_rad, l.first_point_m, l.last_point_m});
      }
      TruthInSensorFrame(event.sensor.truth, &people, &segments);
      for (FeatureScore* s : {&seed_score, &figures.pooled}) {
        ScorePeople(person_points, people, score, s);
        ScorePointsOnWalls(point_features, segments, score, s);
        ScoreLines(lines, segments, score, s);
      }
      ++figures.scans;
    }
    if (frames == 0) throw std::invalid_argument("world figures: the scenario gives no scans");
    figures.seed_recall.push_back(seed_score.PersonRecall());
    figures.seed_precision.push_back(seed_score.PersonPrecision());
  }
  return figures;
}

}  // namespace slammtt
