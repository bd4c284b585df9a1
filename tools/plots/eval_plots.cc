#include "tools/plots/eval_plots.h"

#include <algorithm>

#include "tools/plots/svg_plot.h"

namespace slammtt {
namespace {

constexpr int kMapWidthPx = 820;
constexpr int kMapHeightPx = 700;

const LineStyle kTruthStyle{"#111111", 2.0, "", 1.0};
const LineStyle kOdometryStyle{"#ff7f0e", 1.6, "7 4", 1.0};
const LineStyle kEstimateStyle{"#1f77b4", 1.6, "", 1.0};
const LineStyle kMoverPathStyle{"#9a9a9a", 5.0, "", 0.45};

std::vector<Eigen::Vector2d> Positions(const std::vector<TimedPose>& poses) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(poses.size());
  for (const TimedPose& p : poses) out.emplace_back(p.pose.x_m, p.pose.y_m);
  return out;
}

std::vector<Eigen::Vector2d> Points(const std::vector<IdentifiedPoint>& objects) {
  std::vector<Eigen::Vector2d> out;
  for (const IdentifiedPoint& o : objects) out.push_back(o.position_m);
  return out;
}

const LineStyle kWallStyle{"#8c6d46", 2.2, "", 0.8};
const LineStyle kFurnitureStyle{"#c9a66b", 1.6, "", 0.8};

std::vector<Eigen::Vector2d> SegmentEnds(const std::vector<TruthSegment>& segments) {
  std::vector<Eigen::Vector2d> out;
  for (const TruthSegment& g : segments) {
    out.push_back(g.from_m);
    out.push_back(g.to_m);
  }
  return out;
}

// The true walls and furniture sides under everything else; their legend entries when any.
void DrawStaticSegments(const EvaluationReport& report, PlotPanel* panel,
                        std::vector<LegendEntry>* legend) {
  bool walls = false;
  bool furniture = false;
  for (const TruthSegment& g : report.static_segments) {
    const bool wall = g.kind == TruthKind::kWall;
    panel->Polyline({g.from_m, g.to_m}, wall ? kWallStyle : kFurnitureStyle);
    walls = walls || wall;
    furniture = furniture || !wall;
  }
  if (walls) legend->push_back({"walls (truth)", kWallStyle});
  if (furniture) legend->push_back({"furniture (truth)", kFurnitureStyle});
}

std::string Subtitle(const EvaluationReport& report) {
  return report.source;
}

}  // namespace

std::string TrajectorySvg(const EvaluationReport& report) {
  SvgDocument doc(kMapWidthPx, kMapHeightPx);
  PlotPanel panel(&doc, 0, 0, kMapWidthPx, kMapHeightPx - 16);
  const auto truth = Positions(report.truth_trajectory);
  const auto odometry = report.odometry ? Positions(report.odometry->anchored)
                                        : std::vector<Eigen::Vector2d>{};
  const auto estimate =
      report.robot ? Positions(report.robot->anchored) : std::vector<Eigen::Vector2d>{};
  panel.FitRange({truth, odometry, estimate}, true);
  panel.DrawAxes("Robot trajectory", "x [m]", "y [m]");
  panel.Polyline(truth, kTruthStyle);
  panel.Polyline(odometry, kOdometryStyle);
  panel.Polyline(estimate, kEstimateStyle);
  if (!truth.empty()) panel.Dots({truth.front()}, 5, LineStyle{"#2ca02c"});
  std::vector<LegendEntry> legend = {{"truth", kTruthStyle}};
  if (report.odometry) {
    legend.push_back({"odometry (ATE RMSE " + FormatNumber(report.odometry->error.rmse_m, 3) +
                          " m)",
                      kOdometryStyle});
  }
  if (report.robot) {
    legend.push_back({"estimate (ATE RMSE " + FormatNumber(report.robot->error.rmse_m, 3) + " m)",
                      kEstimateStyle});
  }
  legend.push_back({"start", LineStyle{"#2ca02c"}, LegendMark::kDot});
  panel.Legend(legend);
  if (truth.empty()) panel.Message("no ground truth in the log");
  doc.Text(kMapWidthPx / 2.0, kMapHeightPx - 6, Subtitle(report), 10, "middle", "fill=\"#777777\"");
  return doc.ToString();
}

std::string MapSvg(const EvaluationReport& report) {
  SvgDocument doc(kMapWidthPx, kMapHeightPx);
  PlotPanel panel(&doc, 0, 0, kMapWidthPx, kMapHeightPx - 16);
  const auto truth = Positions(report.truth_trajectory);
  std::vector<Eigen::Vector2d> landmark_points;
  for (const AnchoredLandmark& l : report.landmarks) landmark_points.push_back(l.position_m);
  panel.FitRange({truth, Points(report.static_objects), Points(report.unseen_static_objects),
                  landmark_points, SegmentEnds(report.static_segments)},
                 true);
  panel.DrawAxes("Static map (2-sigma ellipses)", "x [m]", "y [m]");
  std::vector<LegendEntry> segment_legend;
  DrawStaticSegments(report, &panel, &segment_legend);
  for (const auto& path : report.mover_paths) panel.Polyline(path, kMoverPathStyle, 400);
  const LineStyle robot_path{"#111111", 1.0, "3 3", 0.6};
  panel.Polyline(truth, robot_path);
  const LineStyle static_truth{"#111111", 1.6};
  const LineStyle unseen_truth{"#aaaaaa", 1.2};
  panel.Crosses(Points(report.static_objects), 5, static_truth);
  panel.Crosses(Points(report.unseen_static_objects), 4, unseen_truth);
  const LineStyle good{"#1f77b4", 1.3};
  const LineStyle mover{"#d62728", 1.6};
  const LineStyle other{"#ff7f0e", 1.3};
  for (const AnchoredLandmark& l : report.landmarks) {
    const LineStyle& style = l.kind == AnchoredLandmark::Kind::kStatic  ? good
                             : l.kind == AnchoredLandmark::Kind::kMover ? mover
                                                                        : other;
    panel.CovarianceEllipse(l.position_m, l.covariance, 2.0, style);
    panel.Dots({l.position_m}, 2.2, style);
  }
  std::vector<LegendEntry> legend = {
      {"true static object", static_truth, LegendMark::kCross},
      {"landmark on a static object", good, LegendMark::kDot},
      {"landmark on a mover's path", mover, LegendMark::kDot},
      {"other landmark", other, LegendMark::kDot},
      {"true mover paths", kMoverPathStyle},
      {"robot path (truth)", robot_path}};
  legend.insert(legend.end(), segment_legend.begin(), segment_legend.end());
  if (!report.unseen_static_objects.empty()) {
    legend.insert(legend.begin() + 1,
                  {"static object never seen", unseen_truth, LegendMark::kCross});
  }
  panel.Legend(legend);
  if (!report.map) panel.Message("no MAP in the log");
  std::string caption = Subtitle(report);
  if (report.map) {
    caption += ": " + std::to_string(report.map->num_matched) + "/" +
               std::to_string(report.map->num_static_truth) + " static objects found, " +
               std::to_string(report.map->num_movers_in_static_map) + " movers in the map";
  }
  doc.Text(kMapWidthPx / 2.0, kMapHeightPx - 6, caption, 10, "middle", "fill=\"#777777\"");
  return doc.ToString();
}

std::string TracksSvg(const EvaluationReport& report) {
  SvgDocument doc(kMapWidthPx, kMapHeightPx);
  PlotPanel panel(&doc, 0, 0, kMapWidthPx, kMapHeightPx - 16);
  const auto truth = Positions(report.truth_trajectory);
  std::vector<std::vector<Eigen::Vector2d>> sets = report.mover_paths;
  sets.push_back(truth);
  for (const TrackPath& t : report.track_paths) sets.push_back(t.points);
  sets.push_back(SegmentEnds(report.static_segments));
  panel.FitRange(sets, true);
  panel.DrawAxes("Moving objects: tracks per identity over the true paths", "x [m]", "y [m]");
  std::vector<LegendEntry> legend;
  DrawStaticSegments(report, &panel, &legend);
  for (const auto& path : report.mover_paths) panel.Polyline(path, kMoverPathStyle, 600);
  panel.Polyline(truth, LineStyle{"#111111", 1.2, "", 0.8});
  for (const TrackPath& t : report.track_paths) {
    const LineStyle style{IdentityColour(t.id), 1.4};
    if (t.points.size() == 1) {
      panel.Dots(t.points, 2.0, style);
    } else {
      panel.Polyline(t.points, style, 600);
      panel.Dots({t.points.back()}, 2.5, style);
    }
    // The identity at the track's last position, so that a switch can be read off the picture.
    panel.Label(t.points.back(), std::to_string(t.id), style.colour);
  }
  legend.insert(legend.begin(),
                {{"true mover paths", kMoverPathStyle},
                 {"robot (truth)", LineStyle{"#111111", 1.2}},
                 {"confirmed moving track (label: its id), one colour per identity",
                  LineStyle{"#1f77b4", 1.4}},
                 {"where a track ends", LineStyle{"#1f77b4"}, LegendMark::kDot}});
  panel.Legend(legend);
  if (!report.tracking) panel.Message("no TRACKS in the log");
  std::string caption = Subtitle(report);
  if (report.tracking) {
    caption += ": " + std::to_string(report.track_paths.size()) + " track identities, " +
               std::to_string(report.tracking->clear_mot.num_id_switches) + " identity switches";
  }
  doc.Text(kMapWidthPx / 2.0, kMapHeightPx - 6, caption, 10, "middle", "fill=\"#777777\"");
  return doc.ToString();
}

std::string ErrorsSvg(const EvaluationReport& report) {
  const int width = 900;
  const int height = 640;
  SvgDocument doc(width, height);
  const double t0 = static_cast<double>(report.first_utime);
  auto seconds = [&](int64_t utime) { return (static_cast<double>(utime) - t0) * 1e-6; };
  const double t_end = std::max(seconds(report.last_utime), 1e-3);

  PlotPanel top(&doc, 0, 0, width, height / 2.0);
  std::vector<Eigen::Vector2d> estimate;
  std::vector<Eigen::Vector2d> odometry;
  if (report.robot) {
    const TrajectoryError& e = report.robot->error;
    for (size_t k = 0; k < e.utime.size(); ++k) {
      estimate.emplace_back(seconds(e.utime[k]), e.position_error_m[k]);
    }
  }
  if (report.odometry) {
    const TrajectoryError& e = report.odometry->error;
    for (size_t k = 0; k < e.utime.size(); ++k) {
      odometry.emplace_back(seconds(e.utime[k]), e.position_error_m[k]);
    }
  }
  double top_max = 0.1;
  for (const auto* series : {&estimate, &odometry}) {
    for (const Eigen::Vector2d& p : *series) top_max = std::max(top_max, p.y());
  }
  top.SetRange(0.0, t_end, 0.0, 1.08 * top_max, false);
  top.DrawAxes("Robot position error", "time [s]", "error [m]");
  top.Polyline(odometry, kOdometryStyle, 2000);
  top.Polyline(estimate, kEstimateStyle, 2000);
  std::vector<LegendEntry> top_legend;
  if (report.odometry) top_legend.push_back({"odometry", kOdometryStyle});
  if (report.robot) top_legend.push_back({"estimate", kEstimateStyle});
  top.Legend(top_legend);
  if (!report.robot && !report.odometry) top.Message("no estimate and no odometry in the log");

  PlotPanel bottom(&doc, 0, height / 2.0, width, height / 2.0);
  std::vector<Eigen::Vector2d> ospa;
  std::vector<Eigen::Vector2d> gospa;
  double bottom_max = report.options.ospa_cutoff_m;
  if (report.tracking) {
    for (const TrackingScan& s : report.tracking->scans) {
      ospa.emplace_back(seconds(s.utime), s.ospa_m);
      gospa.emplace_back(seconds(s.utime), s.gospa_m);
      bottom_max = std::max(bottom_max, s.gospa_m);
    }
  }
  bottom.SetRange(0.0, t_end, 0.0, 1.08 * bottom_max, false);
  bottom.DrawAxes("Tracking error per scan (c = " + FormatNumber(report.options.ospa_cutoff_m, 1) +
                      " m, p = " + FormatNumber(report.options.ospa_order, 0) + ")",
                  "time [s]", "distance [m]");
  const LineStyle ospa_style{"#2ca02c", 1.3};
  const LineStyle gospa_style{"#9467bd", 1.1, "", 0.8};
  bottom.Polyline(gospa, gospa_style, 2000);
  bottom.Polyline(ospa, ospa_style, 2000);
  if (report.tracking) {
    bottom.Legend({{"OSPA (mean " + FormatNumber(report.tracking->ospa_mean_m, 3) + " m)",
                    ospa_style},
                   {"GOSPA (mean " + FormatNumber(report.tracking->gospa_mean_m, 3) + " m)",
                    gospa_style}});
  } else {
    bottom.Message("no TRACKS in the log");
  }
  return doc.ToString();
}

std::string ScanSvg(const EvaluationReport& report) {
  const int legend_rows = 5;
  const int height = kMapHeightPx + 16 * legend_rows;
  SvgDocument doc(kMapWidthPx, height);
  PlotPanel panel(&doc, 0, 0, kMapWidthPx, kMapHeightPx - 16);
  if (!report.scan_picture) {
    panel.SetRange(-1, 1, -1, 1, true);
    panel.DrawAxes("One scan: beams, lines, points and people", "x [m]", "y [m]");
    panel.Message("no LASER_SCAN with FEATURES of the same utime in the log");
    return doc.ToString();
  }
  const ScanPicture& p = *report.scan_picture;
  const Pose2 sensor = p.sensor_pose.value_or(Pose2{});
  auto world = [&](const Eigen::Vector2d& in_sensor) { return TransformPoint(sensor, in_sensor); };
  std::vector<Eigen::Vector2d> beams;
  for (const Eigen::Vector2d& b : p.scan.beams_m) beams.push_back(world(b));
  std::vector<Eigen::Vector2d> extent = beams;
  extent.push_back(world(Eigen::Vector2d::Zero()));
  panel.FitRange({extent}, true);
  const std::string frame = p.sensor_pose ? "truth frame" : "sensor frame";
  panel.DrawAxes("The scan with the most people: beams, lines, points, people (" + frame + ")",
                 "x [m]", "y [m]");
  std::vector<LegendEntry> legend;
  if (p.sensor_pose) DrawStaticSegments(report, &panel, &legend);
  const LineStyle beam_style{"#777777", 1.0};
  panel.Dots(beams, 1.2, beam_style);
  const LineStyle line_style{"#1f77b4", 3.0, "", 0.8};
  for (const ScanSnapshot::Line& l : p.scan.lines) {
    panel.Polyline({world(l.first_m), world(l.last_m)}, line_style);
  }
  const LineStyle leg_style{"#ff7f0e", 1.4};
  const LineStyle other_style{"#2ca02c", 1.4};
  for (const ScanSnapshot::Point& q : p.scan.points) {
    const double r = std::max(0.03, 0.5 * q.width_m);
    const LineStyle& style = q.leg_likeness >= 0.5 ? leg_style : other_style;
    panel.CovarianceEllipse(world(q.position_m), Eigen::Matrix2d::Identity() * r * r, 1.0, style);
    panel.Dots({world(q.position_m)}, 2.5, style);
  }
  const LineStyle person_style{"#d62728", 1.8};
  for (const ScanSnapshot::Person& person : p.scan.people) {
    const Eigen::Vector2d centre = world(person.position_m);
    for (int leg : person.legs) {
      panel.Polyline({centre, world(p.scan.points[static_cast<size_t>(leg)].position_m)},
                     LineStyle{"#d62728", 1.0, "2 2"});
    }
    panel.Dots({centre}, 7.0, person_style, false);  // a ring: the legs stay visible inside
  }
  const LineStyle truth_leg{"#111111", 1.0};
  std::vector<Eigen::Vector2d> truth_people;
  for (const TruthObjectSample& o : p.objects) {
    if (o.kind == TruthKind::kPerson) truth_people.push_back(o.position_m);
  }
  for (const TruthLeg& leg : p.legs) {
    panel.CovarianceEllipse(leg.position_m, Eigen::Matrix2d::Identity() * leg.radius_m *
                                                leg.radius_m, 1.0, truth_leg);
  }
  panel.Crosses(truth_people, 5, truth_leg);
  panel.Dots({world(Eigen::Vector2d::Zero())}, 5, LineStyle{"#9467bd"});
  legend.insert(legend.begin(),
                {{"beams (valid returns)", beam_style, LegendMark::kDot},
                 {"line features (observed extent)", line_style},
                 {"point feature, leg-like (leg_likeness >= 0.5; circle: its width)", leg_style,
                  LegendMark::kDot},
                 {"point feature, other", other_style, LegendMark::kDot},
                 {"person feature (ring; dashed: its legs)", person_style, LegendMark::kDot},
                 {"true person (cross) and legs (circles)", truth_leg, LegendMark::kCross},
                 {"sensor", LineStyle{"#9467bd"}, LegendMark::kDot}});
  // The legend goes below the panel, in columns, so that it never covers the scan.
  const int columns = 2;
  for (size_t k = 0; k < legend.size(); ++k) {
    const double x = 60.0 + 380.0 * static_cast<double>(k % columns);
    const double y = kMapHeightPx - 10 + 16.0 * static_cast<double>(k / columns);
    const LegendEntry& e = legend[k];
    if (e.mark == LegendMark::kLine) {
      doc.Add("<line x1=\"" + FormatNumber(x, 1) + "\" y1=\"" + FormatNumber(y, 1) + "\" x2=\"" +
              FormatNumber(x + 22, 1) + "\" y2=\"" + FormatNumber(y, 1) + "\" stroke=\"" +
              e.style.colour + "\" stroke-width=\"" + FormatNumber(e.style.width_px, 1) + "\"/>");
    } else {
      doc.Add("<circle cx=\"" + FormatNumber(x + 11, 1) + "\" cy=\"" + FormatNumber(y, 1) +
              "\" r=\"3.5\" fill=\"" + e.style.colour + "\"/>");
    }
    doc.Text(x + 28, y + 4, e.label, 11);
  }
  const std::string caption = Subtitle(report) + ": scan at utime " +
                              std::to_string(p.scan.utime) + ", " +
                              std::to_string(p.scan.lines.size()) + " lines, " +
                              std::to_string(p.scan.points.size()) + " points, " +
                              std::to_string(p.scan.people.size()) + " people";
  doc.Text(kMapWidthPx / 2.0, height - 6, caption, 10, "middle", "fill=\"#777777\"");
  return doc.ToString();
}

std::vector<std::pair<std::string, std::string>> EvaluationPlots(const EvaluationReport& report) {
  return {{"trajectory.svg", TrajectorySvg(report)},
          {"map.svg", MapSvg(report)},
          {"tracks.svg", TracksSvg(report)},
          {"errors.svg", ErrorsSvg(report)},
          {"scan.svg", ScanSvg(report)}};
}

}  // namespace slammtt
