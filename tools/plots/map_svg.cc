#include "tools/plots/map_svg.h"

#include <vector>

#include "tools/plots/label_placement.h"
#include "tools/plots/picture_style.h"

namespace slammtt {
namespace {

const LineStyle kStaticTruth{"#111111", 1.6};
const LineStyle kUnseenTruth{"#aaaaaa", 1.2};
const LineStyle kGood{"#1f77b4", 1.3};
const LineStyle kMover{"#d62728", 1.6};
const LineStyle kOther{"#ff7f0e", 1.3};
const LineStyle kUnjudged{"#3b6fb6", 1.3};
const LineStyle kRobotPath{"#111111", 1.0, "3 3", 0.6};
const LineStyle kLineLandmark{"#1f77b4", 1.4, "5 2", 1.0};
constexpr int kLabelPx = 9;

const LineStyle& LandmarkStyle(AnchoredLandmark::Kind kind) {
  switch (kind) {
    case AnchoredLandmark::Kind::kStatic: return kGood;
    case AnchoredLandmark::Kind::kMover: return kMover;
    case AnchoredLandmark::Kind::kUnjudged: return kUnjudged;
    default: return kOther;
  }
}

// Every landmark's id beside it, in its colour.
void DrawLandmarkIds(const EvaluationReport& report, PlotPanel* panel) {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::string> texts;
  for (const AnchoredLandmark& l : report.landmarks) {
    points.push_back(panel->ToPixel(l.position_m));
    texts.push_back(std::to_string(l.id));
  }
  const std::vector<PlacedLabel> labels = PlaceLabels(points, texts, kLabelPx, 2.5);
  for (size_t k = 0; k < labels.size(); ++k) {
    panel->LabelAtPixel(labels[k].corner_px, texts[k], kLabelPx,
                        LandmarkStyle(report.landmarks[k].kind).colour);
  }
}

}  // namespace

std::string MapSvg(const EvaluationReport& report) {
  SvgDocument doc(kPictureWidthPx, kMapPanelHeightPx);
  PlotPanel panel(&doc, 0, 0, kPictureWidthPx, kMapPanelHeightPx);
  const bool truth = !report.log_only;
  const auto robot_path = truth ? Positions(report.truth_trajectory) : EstimatedPath(report);
  std::vector<Eigen::Vector2d> landmark_points;
  for (const AnchoredLandmark& l : report.landmarks) landmark_points.push_back(l.position_m);
  panel.FitRange({robot_path, Points(report.static_objects), Points(report.unseen_static_objects),
                  landmark_points, SegmentEnds(report.static_segments)},
                 true);
  panel.DrawAxes("Static map (2-sigma ellipses, landmark ids; " + PictureFrame(report) + ")",
                 "x [m]", "y [m]");
  std::vector<LegendEntry> segment_legend;
  DrawStaticSegments(report, &panel, &segment_legend);
  for (const auto& path : report.mover_paths) panel.Polyline(path, MoverPathStyle(), 400);
  panel.Polyline(robot_path, kRobotPath);
  panel.Crosses(Points(report.static_objects), 5, kStaticTruth);
  panel.Crosses(Points(report.unseen_static_objects), 4, kUnseenTruth);
  for (const AnchoredLandmark& l : report.landmarks) {
    const LineStyle& style = LandmarkStyle(l.kind);
    panel.CovarianceEllipse(l.position_m, l.covariance, 2.0, style);
    panel.Dots({l.position_m}, 2.2, style);
  }
  DrawLandmarkIds(report, &panel);
  // Line landmarks: the stretch of each the estimator saw, over the true surfaces.
  for (const EstimatedLine& l : report.lines) panel.Polyline({l.from_m, l.to_m}, kLineLandmark);
  std::vector<LegendEntry> legend;
  if (truth) {
    legend = {{"true static object", kStaticTruth, LegendMark::kCross},
              {"landmark on a static object (label: its id)", kGood, LegendMark::kDot},
              {"landmark on a mover's path", kMover, LegendMark::kDot},
              {"other landmark", kOther, LegendMark::kDot},
              {"true mover paths", MoverPathStyle()},
              {"robot path (truth)", kRobotPath}};
    if (!report.unseen_static_objects.empty()) {
      legend.insert(legend.begin() + 1,
                    {"static object never seen", kUnseenTruth, LegendMark::kCross});
    }
  } else {
    legend = {{"landmark (label: its id; no ground truth to judge it)", kUnjudged,
               LegendMark::kDot},
              {"robot path (estimate)", kRobotPath}};
  }
  if (!report.lines.empty()) legend.push_back({"line landmark (seen extent)", kLineLandmark});
  legend.insert(legend.end(), segment_legend.begin(), segment_legend.end());
  const bool has_map = report.map || (report.log_only && report.log_only->has_map);
  if (!has_map) panel.Message("no MAP in the log");
  std::string caption = Subtitle(report);
  if (report.map) {
    caption += ": " + std::to_string(report.map->num_matched) + "/" +
               std::to_string(report.map->num_static_truth) + " static objects found, " +
               std::to_string(report.map->num_movers_in_static_map) + " movers in the map";
  } else if (report.log_only) {
    caption += ": " + std::to_string(report.landmarks.size()) + " landmarks in the last MAP";
  }
  if (report.line_map) {
    caption += ", " + std::to_string(report.line_map->matches.size()) + "/" +
               std::to_string(report.line_map->num_lines) + " line landmarks on a true surface";
  }
  AppendLegendAndCaption(&doc, panel, legend, caption);
  return doc.ToString();
}

}  // namespace slammtt
