#include "tools/legs/world_figures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angle.h"

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

// The legs of person `person_id` among the truth's objects.
std::vector<const ObjectTruth*> LegsOf(const TruthSnapshot& truth, int64_t person_id) {
  std::vector<const ObjectTruth*> legs;
  for (const ObjectTruth& o : truth.objects) {
    if (o.kind == ObjectKind::kLeg && o.parent_id == person_id) legs.push_back(&o);
  }
  return legs;
}

// A person feature's centre in the sensor frame.
Eigen::Vector2d CentreOf(const PersonFeature& p) {
  return p.range_m * Eigen::Vector2d(std::cos(p.bearing_rad), std::sin(p.bearing_rad));
}

// People with the beams of their most visible leg, and the static surfaces, in the sensor
// frame; person_objects[i]: the index of people[i] in truth.objects.
void TruthInSensorFrame(const TruthSnapshot& truth, std::vector<TruthPerson>* people,
                        std::vector<TruthSegment>* segments, std::vector<size_t>* person_objects) {
  const SensorFrameOf to_sensor(truth.robot.sensor_pose);
  people->clear();
  segments->clear();
  person_objects->clear();
  for (size_t i = 0; i < truth.objects.size(); ++i) {
    const ObjectTruth& o = truth.objects[i];
    if (o.kind != ObjectKind::kPerson) continue;
    person_objects->push_back(i);
    TruthPerson person;
    person.centre_m = to_sensor(o.x_m, o.y_m);
    for (const ObjectTruth* leg : LegsOf(truth, o.id)) {
      person.max_leg_beams = std::max(person.max_leg_beams, leg->beams_on_object);
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

double CcwDelta(double a_rad, double b_rad) {
  const double d = WrapAngle(b_rad) - WrapAngle(a_rad);
  return d < 0.0 ? d + 2.0 * M_PI : d;
}

// Within this distance of a wall's end a hit is on the end (a door jamb, a corner).
constexpr double kWallEndM = 0.15;

struct LegOrigin {
  LegSource source = LegSource::kMixedPixel;
  int64_t person_id = -1;  // kPersonLeg: the id of the leg's person
};

// The source of the cluster of `feature` (its beams: those from its first to its last beam
// counter-clockwise): the most frequent first surface of its valid beams.
LegOrigin OriginOf(const Feature& feature, const SensorFrame& frame) {
  LegOrigin origin;
  const std::vector<SimulatedBeam>& scan = frame.scan;
  if (feature.first_beam_index < 0 || feature.last_beam_index < 0) return origin;
  const double first = scan[static_cast<size_t>(feature.first_beam_index)].angle_rad;
  const double span = CcwDelta(first, scan[static_cast<size_t>(feature.last_beam_index)].angle_rad);
  const Pose2D& sensor = frame.truth.robot.sensor_pose;
  int64_t counts[kLegSources] = {};
  int64_t wall_beams = 0;
  bool wall_end = false;
  int first_wall = -1;
  std::vector<std::pair<int64_t, int64_t>> person_beams;  // (person id, beams)
  for (const SimulatedBeam& beam : scan) {
    if (!beam.valid || CcwDelta(first, beam.angle_rad) > span + 1e-9) continue;
    if (beam.mixed_pixel) {
      ++counts[static_cast<int>(LegSource::kMixedPixel)];
    } else if (beam.object >= 0) {
      const ObjectTruth& o = frame.truth.objects[static_cast<size_t>(beam.object)];
      LegSource source = LegSource::kPost;
      if (o.kind == ObjectKind::kLeg) {
        source = LegSource::kPersonLeg;
        auto it = std::find_if(person_beams.begin(), person_beams.end(),
                               [&](const auto& p) { return p.first == o.parent_id; });
        if (it == person_beams.end()) {
          person_beams.emplace_back(o.parent_id, 1);
        } else {
          ++it->second;
        }
      } else if (o.kind == ObjectKind::kFurniture) {
        source = LegSource::kFurnitureLeg;
      }
      ++counts[static_cast<int>(source)];
    } else if (beam.segment >= 0) {
      const SegmentTruth& s = frame.truth.segments[static_cast<size_t>(beam.segment)];
      if (s.kind != ObjectKind::kWall) {
        ++counts[static_cast<int>(LegSource::kFurnitureSide)];
        continue;
      }
      ++wall_beams;
      const double a = sensor.heading_rad + beam.angle_rad;
      const double hx = sensor.x_m + beam.true_range_m * std::cos(a);
      const double hy = sensor.y_m + beam.true_range_m * std::sin(a);
      wall_end = wall_end || std::hypot(hx - s.segment.x0_m, hy - s.segment.y0_m) <= kWallEndM ||
                 std::hypot(hx - s.segment.x1_m, hy - s.segment.y1_m) <= kWallEndM ||
                 (first_wall >= 0 && first_wall != beam.segment);
      if (first_wall < 0) first_wall = beam.segment;
    }
  }
  counts[static_cast<int>(wall_end ? LegSource::kWallEnd : LegSource::kWallPiece)] = wall_beams;
  int best = static_cast<int>(LegSource::kMixedPixel);
  for (int k = 0; k < kLegSources; ++k) {
    if (counts[k] > counts[best]) best = k;
  }
  origin.source = static_cast<LegSource>(best);
  if (origin.source == LegSource::kPersonLeg) {
    origin.person_id = std::max_element(person_beams.begin(), person_beams.end(),
                                        [](const auto& a, const auto& b) {
                                          return a.second < b.second;
                                        })->first;
  }
  return origin;
}

// A false one-leg person on a leg of person `person_id`: when no feature of the scan matched that
// person (it is in the truth set), the feature was the person's only one and too far from its
// centre; records how far, and how far the person's farther leg is from its centre.
void AddLoneLegOfAPerson(const PersonFeature& p, int64_t person_id,
                         const std::vector<TruthPerson>& people,
                         const std::vector<size_t>& person_objects,
                         const std::vector<uint8_t>& matched, const SensorFrame& frame,
                         PersonCauses* causes) {
  const SensorFrameOf to_sensor(frame.truth.robot.sensor_pose);
  for (size_t j = 0; j < people.size(); ++j) {
    const ObjectTruth& person = frame.truth.objects[person_objects[j]];
    if (person.id != person_id || matched[j]) continue;
    double farther_leg_m = 0.0;
    for (const ObjectTruth* leg : LegsOf(frame.truth, person.id)) {
      farther_leg_m =
          std::max(farther_leg_m, (to_sensor(leg->x_m, leg->y_m) - people[j].centre_m).norm());
    }
    causes->false_one_leg_alone_to_centre_m.push_back((people[j].centre_m - CentreOf(p)).norm());
    causes->false_one_leg_alone_farther_leg_m.push_back(farther_leg_m);
  }
}

// Adds one scan's person features to `causes` (outcome: ScorePeople's, per person feature).
void AddCauses(const Segmenter& segmenter, const SensorFrame& frame,
               const std::vector<TruthPerson>& people, const std::vector<size_t>& person_objects,
               const std::vector<int>& outcome, const FeatureScoreOptions& score,
               PersonCauses* causes) {
  const std::vector<Feature>& features = segmenter.features();
  const std::vector<PersonFeature>& found = segmenter.people();
  const auto leg_of = [&](int32_t index) { return OriginOf(features[size_t(index)], frame); };
  const SensorFrameOf to_sensor(frame.truth.robot.sensor_pose);
  std::vector<uint8_t> matched(people.size(), 0);
  for (size_t i = 0; i < found.size(); ++i) {
    if (outcome[i] >= 0) matched[static_cast<size_t>(outcome[i])] = 1;
  }
  for (size_t i = 0; i < found.size(); ++i) {
    const PersonFeature& p = found[i];
    if (outcome[i] == kPersonFalse) {
      const LegOrigin origin = leg_of(p.leg_index[0]);
      const int a = static_cast<int>(origin.source);
      if (p.num_legs == 1) {
        ++causes->false_one_leg[a];
        if (origin.source == LegSource::kPersonLeg) {
          AddLoneLegOfAPerson(p, origin.person_id, people, person_objects, matched, frame,
                              causes);
        }
      } else {
        const int b = static_cast<int>(leg_of(p.leg_index[1]).source);
        ++causes->false_pairs[std::min(a, b)][std::max(a, b)];
      }
      continue;
    }
    if (outcome[i] < 0) continue;
    const size_t j = static_cast<size_t>(outcome[i]);
    const Eigen::Vector2d at = CentreOf(p);
    const Eigen::Vector2d error = people[j].centre_m - at;
    const ObjectTruth& person = frame.truth.objects[person_objects[j]];
    if (p.num_legs == 2) {
      causes->pair_errors_m.push_back(error.norm());
      const std::vector<const ObjectTruth*> legs = LegsOf(frame.truth, person.id);
      Eigen::Vector2d legs_sum = Eigen::Vector2d::Zero();
      for (const ObjectTruth* leg : legs) legs_sum += to_sensor(leg->x_m, leg->y_m);
      if (legs.size() == 2) {
        causes->pair_errors_to_legs_m.push_back((0.5 * legs_sum - at).norm());
        causes->pair_body_to_legs_m.push_back((0.5 * legs_sum - people[j].centre_m).norm());
      }
      const LegOrigin a = leg_of(p.leg_index[0]);
      const LegOrigin b = leg_of(p.leg_index[1]);
      const bool one = a.source == LegSource::kPersonLeg && b.source == LegSource::kPersonLeg &&
                       a.person_id == person.id && b.person_id == person.id;
      ++(one ? causes->pairs_of_one_person : causes->pairs_mixed);
      continue;
    }
    causes->one_leg_errors_m.push_back(error.norm());
    const Eigen::Vector2d along = at.normalized();
    causes->one_leg_radial_m.push_back(error.dot(along));
    causes->one_leg_lateral_m.push_back(along.x() * error.y() - along.y() * error.x());
    int fewest = 1 << 30;
    for (const ObjectTruth* leg : LegsOf(frame.truth, person.id)) {
      fewest = std::min(fewest, leg->beams_on_object);
    }
    causes->one_leg_other_hidden += fewest < 3;
  }
  // Missed people: the best fate of the clusters near their legs.
  const double threshold = segmenter.options().leg_threshold;
  for (size_t j = 0; j < people.size(); ++j) {
    if (matched[j] || people[j].max_leg_beams < score.min_leg_beams ||
        people[j].centre_m.norm() > score.max_range_m) {
      continue;
    }
    const ObjectTruth& person = frame.truth.objects[person_objects[j]];
    int best = 5;
    for (const ObjectTruth& leg : frame.truth.objects) {
      if (leg.kind != ObjectKind::kLeg || leg.parent_id != person.id) continue;
      const Eigen::Vector2d at = to_sensor(leg.x_m, leg.y_m);
      for (const LegClusterRecord& r : segmenter.leg_clusters()) {
        if (std::hypot(r.centroid_x_m - at.x(), r.centroid_y_m - at.y()) > 0.15) continue;
        int fate = 0;
        switch (r.fate) {
          case LegClusterFate::kPointFeature: fate = r.leg_likeness >= threshold ? 0 : 1; break;
          case LegClusterFate::kOnALine: fate = 2; break;
          case LegClusterFate::kStructurePiece: fate = 3; break;
          case LegClusterFate::kNotALeg: fate = 4; break;
        }
        best = std::min(best, fate);
      }
    }
    ++causes->missed_by_fate[best];
  }
}

}  // namespace

const char* LegSourceName(LegSource source) {
  switch (source) {
    case LegSource::kPersonLeg: return "person leg";
    case LegSource::kWallEnd: return "wall end";
    case LegSource::kWallPiece: return "wall piece";
    case LegSource::kFurnitureSide: return "furniture side";
    case LegSource::kFurnitureLeg: return "chair/table leg";
    case LegSource::kPost: return "post";
    case LegSource::kMixedPixel: return "mixed pixel";
  }
  return "?";
}

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
  std::vector<size_t> person_objects;
  std::vector<int> outcome;
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
      TruthInSensorFrame(event.sensor.truth, &people, &segments, &person_objects);
      for (FeatureScore* s : {&seed_score, &figures.pooled}) {
        ScorePeople(person_points, people, score, s, &outcome);
        ScorePointsOnWalls(point_features, segments, score, s);
        ScoreLines(lines, segments, score, s);
      }
      AddCauses(segmenter, event.sensor, people, person_objects, outcome, score,
                &figures.causes);
      ++figures.scans;
    }
    if (frames == 0) throw std::invalid_argument("world figures: the scenario gives no scans");
    figures.seed_recall.push_back(seed_score.PersonRecall());
    figures.seed_precision.push_back(seed_score.PersonPrecision());
  }
  return figures;
}

}  // namespace slammtt
