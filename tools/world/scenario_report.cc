#include "tools/world/scenario_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace slammtt {

ScenarioReporter::ScenarioReporter(const LaserSpec& laser, double robot_radius_m)
    : laser_(laser), robot_radius_m_(robot_radius_m), period_s_(1.0 / laser.rate_hz) {
  report_.scan_period_s = period_s_;
  report_.min_statics_visible = 1 << 30;
  report_.min_movers_visible = 1 << 30;
}

namespace {

void Closer(ClosestApproach* best, double gap, int64_t a, int64_t b, double t) {
  if (gap < best->gap_m) *best = ClosestApproach{gap, a, b, t};
}

}  // namespace

void ScenarioReporter::AddScan(const SensorFrame& frame) {
  const TruthSnapshot& truth = frame.truth;
  const double t = static_cast<double>(frame.time_us) * 1e-6;
  ++report_.scans;
  const Pose2D& robot = truth.robot.pose;
  if (have_previous_) {
    report_.robot_path_m +=
        std::hypot(robot.x_m - previous_pose_.x_m, robot.y_m - previous_pose_.y_m);
  }
  have_previous_ = true;
  previous_pose_ = robot;
  report_.robot_max_speed_mps =
      std::max(report_.robot_max_speed_mps, std::abs(truth.robot.linear_mps));

  const Pose2D& sensor = truth.robot.sensor_pose;
  const bool full_circle = laser_.fov_deg >= 360.0 - 1e-9;
  const double half_fov = 0.5 * laser_.fov_deg * M_PI / 180.0;
  int statics_visible = 0;
  int movers_visible = 0;
  // The surfaces the laser can hit (every object but a person) and the walls.
  std::vector<Circle> circles;
  std::vector<size_t> circle_object;
  for (size_t i = 0; i < truth.objects.size(); ++i) {
    const ObjectTruth& o = truth.objects[i];
    if (o.kind == ObjectKind::kPerson) continue;
    circles.push_back(Circle{o.x_m, o.y_m, o.radius_m});
    circle_object.push_back(i);
  }
  std::vector<Segment> walls;
  for (const SegmentTruth& s : truth.segments) walls.push_back(s.segment);
  for (const SimulatedBeam& beam : frame.scan) {
    if (beam.dropout) ++report_.dropouts;
    if (!beam.valid) continue;
    ++report_.valid_beams;
    if (beam.mixed_pixel) ++report_.mixed_pixels;
    if (beam.segment >= 0) {
      ++report_.beams_on_segments;
      if (truth.segments[static_cast<size_t>(beam.segment)].kind == ObjectKind::kWall) {
        ++report_.beams_on_walls;
      }
    } else if (beam.object >= 0 &&
               truth.objects[static_cast<size_t>(beam.object)].kind == ObjectKind::kLeg) {
      ++report_.beams_on_legs;
    }
  }
  // The mover a surface belongs to (a leg: its person), for gaps.
  auto owner = [](const ObjectTruth& o) {
    return o.kind == ObjectKind::kLeg ? o.parent_id : o.id;
  };
  for (size_t i = 0; i < truth.objects.size(); ++i) {
    const ObjectTruth& o = truth.objects[i];
    const bool surface = o.kind != ObjectKind::kPerson;
    if (surface) {
      Closer(o.is_static ? &report_.robot_static : &report_.robot_mover,
             std::hypot(o.x_m - robot.x_m, o.y_m - robot.y_m) - o.radius_m - robot_radius_m_, -1,
             owner(o), t);
    }
    for (size_t j = i + 1; j < truth.objects.size(); ++j) {
      const ObjectTruth& p = truth.objects[j];
      if (o.is_static && p.is_static) continue;
      const double gap = std::hypot(o.x_m - p.x_m, o.y_m - p.y_m) - o.radius_m - p.radius_m;
      if (o.is_static || p.is_static) {
        // A mover's surfaces against static circles.
        const ObjectTruth& mover = o.is_static ? p : o;
        if (mover.kind != ObjectKind::kPerson) {
          Closer(&report_.mover_static, gap, owner(mover), o.is_static ? o.id : p.id, t);
        }
      } else if (o.kind != ObjectKind::kPerson && p.kind != ObjectKind::kPerson &&
                 owner(o) != owner(p)) {
        Closer(&report_.mover_mover, gap, owner(o), owner(p), t);  // discs and legs
      }
    }
    if (!o.is_static && surface) {
      for (size_t k = 0; k < walls.size(); ++k) {
        Closer(&report_.mover_static,
               std::sqrt(SquaredDistanceToSegment(o.x_m, o.y_m, walls[k])) - o.radius_m, owner(o),
               truth.segments[k].id, t);
      }
    }
    if (o.is_static) {
      statics_visible += o.visible ? 1 : 0;
      continue;
    }
    const double range = std::hypot(o.x_m - sensor.x_m, o.y_m - sensor.y_m);
    const double bearing =
        WrapAngle(std::atan2(o.y_m - sensor.y_m, o.x_m - sensor.x_m) - sensor.heading_rad);
    const bool in_view = (full_circle || std::abs(bearing) <= half_fov) &&
                         range >= laser_.min_range_m && range <= laser_.max_range_m;
    if (o.kind == ObjectKind::kLeg) continue;  // legs are counted with their person below
    if (o.kind == ObjectKind::kPerson && in_view && i + 2 < truth.objects.size()) {
      for (size_t leg = i + 1; leg <= i + 2; ++leg) {
        const int beams = truth.objects[leg].beams_on_object;
        const int other = truth.objects[leg == i + 1 ? i + 2 : i + 1].beams_on_object;
        ++report_.legs_in_view;
        report_.beams_on_legs_in_view += beams;
        if (beams >= 1) ++report_.legs_with_beams;
        if (beams >= 3) ++report_.legs_with_3_beams;
        if (beams == 0 && other > 0) ++report_.legs_hidden_while_other_seen;
      }
    }
    if (movers_.count(o.id) == 0) order_.push_back(o.id);
    MoverState& m = movers_[o.id];
    m.report.id = o.id;
    m.report.exists_s += period_s_;
    if (in_view) m.report.in_view_s += period_s_;
    if (o.visible) {
      ++movers_visible;
      m.report.visible_s += period_s_;
      m.visible_run_s += period_s_;
      m.report.longest_visible_s = std::max(m.report.longest_visible_s, m.visible_run_s);
    } else {
      m.visible_run_s = 0.0;
    }
    const bool occluded = in_view && !o.visible;
    if (occluded) {
      if (!m.occluded) {
        ++m.report.occlusions;
        OcclusionEpisode episode;
        episode.id = o.id;
        episode.start_s = t;
        const BeamHit hit = CastRay(sensor.x_m, sensor.y_m,
                                    std::atan2(o.y_m - sensor.y_m, o.x_m - sensor.x_m), circles,
                                    walls);
        episode.occluder_id = -1;
        if (hit.segment >= 0) {
          episode.occluder_id = truth.segments[static_cast<size_t>(hit.segment)].id;
          episode.occluder_is_static = true;
        } else if (hit.circle >= 0) {
          const ObjectTruth& occluder =
              truth.objects[circle_object[static_cast<size_t>(hit.circle)]];
          if (owner(occluder) != o.id) {
            episode.occluder_id = owner(occluder);
            episode.occluder_is_static = occluder.is_static;
          }
        }
        m.episode = report_.occlusions.size();
        report_.occlusions.push_back(episode);
      }
      report_.occlusions[m.episode].end_s = t;
      m.occlusion_s += period_s_;
      m.report.longest_occlusion_s = std::max(m.report.longest_occlusion_s, m.occlusion_s);
    } else {
      m.occlusion_s = 0.0;
    }
    m.occluded = occluded;
  }
  for (size_t k = 0; k < walls.size(); ++k) {
    Closer(&report_.robot_static,
           std::sqrt(SquaredDistanceToSegment(robot.x_m, robot.y_m, walls[k])) - robot_radius_m_,
           -1, truth.segments[k].id, t);
  }
  if (statics_visible < report_.min_statics_visible) {
    report_.min_statics_visible = statics_visible;
    report_.min_statics_visible_time_s = t;
  }
  if (statics_visible < 3) ++report_.scans_with_fewer_than_3_statics;
  report_.min_movers_visible = std::min(report_.min_movers_visible, movers_visible);
  movers_visible_sum_ += movers_visible;
  statics_visible_sum_ += statics_visible;
}

ScenarioReport ScenarioReporter::Finish() const {
  ScenarioReport report = report_;
  if (report.scans == 0) {
    report.min_statics_visible = 0;
    report.min_movers_visible = 0;
  }
  report.mean_movers_visible =
      report.scans > 0 ? static_cast<double>(movers_visible_sum_) / report.scans : 0.0;
  report.mean_statics_visible =
      report.scans > 0 ? static_cast<double>(statics_visible_sum_) / report.scans : 0.0;
  for (int64_t id : order_) report.movers.push_back(movers_.at(id).report);
  return report;
}

ScenarioReport ReportScenario(const Scenario& scenario, uint64_t seed) {
  WorldSimulator world(scenario, seed, scenario.output);
  ScenarioReporter reporter(scenario.laser);
  while (!world.Done()) {
    const WorldEvent event = world.Next();
    if (event.kind == WorldEvent::Kind::kSensor) reporter.AddScan(event.sensor);
  }
  return reporter.Finish();
}

std::string FormatScenarioReport(const ScenarioReport& r) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2);
  auto approach = [&](const char* what, const ClosestApproach& a) {
    out << "closest " << what << ": gap " << a.gap_m << " m (ids " << a.id_a << ", " << a.id_b
        << ") at " << a.time_s << " s\n";
  };
  out << "scans " << r.scans << ", robot path " << r.robot_path_m << " m, max speed "
      << r.robot_max_speed_mps << " m/s\n";
  out << "static objects visible per scan: min " << r.min_statics_visible << " (first at "
      << r.min_statics_visible_time_s << " s), mean " << r.mean_statics_visible
      << ", scans with fewer than 3: " << r.scans_with_fewer_than_3_statics << "\n";
  out << "movers visible per scan: min " << r.min_movers_visible << ", mean "
      << r.mean_movers_visible << "\n";
  if (r.mover_mover.gap_m < 1e299) approach("mover-mover", r.mover_mover);
  if (r.mover_static.gap_m < 1e299) approach("mover-static", r.mover_static);
  if (r.robot_static.gap_m < 1e299) approach("robot-static (robot radius 0.26 m)", r.robot_static);
  if (r.robot_mover.gap_m < 1e299) approach("robot-mover (robot radius 0.26 m)", r.robot_mover);
  auto share = [](int64_t part, int64_t whole) {
    return whole > 0 ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
  };
  out << "valid beams " << r.valid_beams << ": on static segments "
      << share(r.beams_on_segments, r.valid_beams) << " % (walls "
      << share(r.beams_on_walls, r.valid_beams) << " %), on legs "
      << share(r.beams_on_legs, r.valid_beams) << " %, mixed pixels "
      << share(r.mixed_pixels, r.valid_beams) << " %; dropouts " << r.dropouts << "\n";
  if (r.legs_in_view > 0) {
    out << "legs of people in view: " << r.legs_in_view
        << " (leg, scan) pairs, beams per leg mean "
        << static_cast<double>(r.beams_on_legs_in_view) / static_cast<double>(r.legs_in_view)
        << ", with >= 1 beam " << share(r.legs_with_beams, r.legs_in_view) << " %, >= 3 beams "
        << share(r.legs_with_3_beams, r.legs_in_view) << " %, hidden while the other leg is seen "
        << share(r.legs_hidden_while_other_seen, r.legs_in_view) << " %\n";
  }
  out << "movers: " << r.movers.size()
      << " (id: exists / in view / visible s, occlusions, longest occlusion s, "
      << "longest visible s)\n";
  for (const MoverReport& m : r.movers) {
    out << "  " << m.id << ": " << m.exists_s << " / " << m.in_view_s << " / " << m.visible_s
        << ", " << m.occlusions << ", " << m.longest_occlusion_s << ", " << m.longest_visible_s
        << "\n";
  }
  out << "occlusions: " << r.occlusions.size() << " (mover hidden by occluder, from - to s)\n";
  for (const OcclusionEpisode& e : r.occlusions) {
    out << "  " << e.id << " by " << e.occluder_id << (e.occluder_is_static ? " (static)" : "")
        << ": " << e.start_s << " - " << e.end_s << "\n";
  }
  return out.str();
}

}  // namespace slammtt
