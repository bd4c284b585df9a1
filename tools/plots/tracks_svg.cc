#include "tools/plots/tracks_svg.h"

#include <vector>

#include "tools/plots/picture_style.h"

namespace slammtt {

std::string TracksSvg(const EvaluationReport& report) {
  SvgDocument doc(kPictureWidthPx, kMapPanelHeightPx);
  PlotPanel panel(&doc, 0, 0, kPictureWidthPx, kMapPanelHeightPx);
  const bool truth = !report.log_only;
  const auto robot_path = truth ? Positions(report.truth_trajectory) : EstimatedPath(report);
  std::vector<std::vector<Eigen::Vector2d>> sets = report.mover_paths;
  sets.push_back(robot_path);
  for (const TrackPath& t : report.track_paths) sets.push_back(t.points);
  sets.push_back(SegmentEnds(report.static_segments));
  panel.FitRange(sets, true);
  panel.DrawAxes(truth ? "Moving objects: tracks per identity over the true paths"
                       : "Moving objects: tracks per identity (" + PictureFrame(report) + ")",
                 "x [m]", "y [m]");
  std::vector<LegendEntry> segment_legend;
  DrawStaticSegments(report, &panel, &segment_legend);
  for (const auto& path : report.mover_paths) panel.Polyline(path, MoverPathStyle(), 600);
  const LineStyle robot_style{"#111111", 1.2, "", 0.8};
  panel.Polyline(robot_path, robot_style);
  for (const TrackPath& t : report.track_paths) {
    const LineStyle style{IdentityColour(t.id), 1.4};
    if (t.points.size() == 1) {
      panel.Dots(t.points, 2.0, style);
    } else {
      panel.Polyline(t.points, style, 600);
      panel.Dots({t.points.back()}, 2.5, style);
    }
    panel.Label(t.points.back(), std::to_string(t.id), style.colour);
  }
  std::vector<LegendEntry> legend;
  if (truth) legend.push_back({"true mover paths", MoverPathStyle()});
  legend.push_back({truth ? "robot (truth)" : "robot (estimate)", robot_style});
  legend.push_back({"confirmed moving track (label: its id), one colour per identity",
                    LineStyle{"#1f77b4", 1.4}});
  legend.push_back({"where a track ends", LineStyle{"#1f77b4"}, LegendMark::kDot});
  legend.insert(legend.end(), segment_legend.begin(), segment_legend.end());
  const bool has_tracks = report.tracking || (report.log_only && report.log_only->has_tracks);
  if (!has_tracks) panel.Message("no TRACKS in the log");
  std::string caption = Subtitle(report);
  if (report.tracking) {
    caption += ": " + std::to_string(report.track_paths.size()) + " track identities, " +
               std::to_string(report.tracking->clear_mot.num_id_switches) + " identity switches";
  } else if (report.log_only) {
    caption += ": " + std::to_string(report.track_paths.size()) + " track identities";
  }
  AppendLegendAndCaption(&doc, panel, legend, caption);
  return doc.ToString();
}

}  // namespace slammtt
