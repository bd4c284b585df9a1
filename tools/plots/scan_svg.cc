#include "tools/plots/scan_svg.h"

#include <algorithm>
#include <vector>

#include "tools/plots/picture_style.h"

namespace slammtt {

std::string ScanSvg(const EvaluationReport& report) {
  SvgDocument doc(kPictureWidthPx, kMapPanelHeightPx);
  PlotPanel panel(&doc, 0, 0, kPictureWidthPx, kMapPanelHeightPx);
  if (!report.scan_picture) {
    panel.SetRange(-1, 1, -1, 1, true);
    panel.DrawAxes("One scan: beams, lines, points and people", "x [m]", "y [m]");
    panel.Message("no LASER_SCAN with FEATURES of the same utime in the log");
    AppendLegendAndCaption(&doc, panel, {}, Subtitle(report));
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
  std::vector<LegendEntry> segment_legend;
  if (p.sensor_pose) DrawStaticSegments(report, &panel, &segment_legend);
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
  std::vector<LegendEntry> legend = {
      {"beams (valid returns)", beam_style, LegendMark::kDot},
      {"line features (observed extent)", line_style},
      {"point feature, leg-like (leg_likeness >= 0.5; circle: its width)", leg_style,
       LegendMark::kDot},
      {"point feature, other", other_style, LegendMark::kDot},
      {"person feature (ring; dashed: its legs)", person_style, LegendMark::kDot},
      {"true person (cross) and legs (circles)", truth_leg, LegendMark::kCross},
      {"sensor", LineStyle{"#9467bd"}, LegendMark::kDot}};
  legend.insert(legend.end(), segment_legend.begin(), segment_legend.end());
  const std::string caption = Subtitle(report) + ": scan at utime " +
                              std::to_string(p.scan.utime) + ", " +
                              std::to_string(p.scan.lines.size()) + " lines, " +
                              std::to_string(p.scan.points.size()) + " points, " +
                              std::to_string(p.scan.people.size()) + " people";
  AppendLegendAndCaption(&doc, panel, legend, caption);
  return doc.ToString();
}

}  // namespace slammtt
