#include "tools/plots/trajectory_svg.h"

#include <vector>

#include "tools/plots/picture_style.h"

namespace slammtt {

std::string TrajectorySvg(const EvaluationReport& report) {
  SvgDocument doc(kPictureWidthPx, kMapPanelHeightPx);
  PlotPanel panel(&doc, 0, 0, kPictureWidthPx, kMapPanelHeightPx);
  const auto truth = Positions(report.truth_trajectory);
  const auto odometry = OdometryPath(report);
  const auto estimate = EstimatedPath(report);
  const std::vector<Eigen::Vector2d> smoothed =
      report.smoothed_robot ? Positions(report.smoothed_robot->anchored)
                            : std::vector<Eigen::Vector2d>();
  panel.FitRange({truth, odometry, estimate, smoothed}, true);
  panel.DrawAxes("Robot trajectory (" + PictureFrame(report) + ")", "x [m]", "y [m]");
  panel.Polyline(truth, TruthStyle());
  panel.Polyline(odometry, OdometryStyle());
  panel.Polyline(estimate, EstimateStyle());
  if (!smoothed.empty()) panel.Polyline(smoothed, SmoothedStyle());
  const LineStyle start{"#2ca02c"};
  for (const auto* path : {&truth, &estimate, &odometry}) {
    if (path->empty()) continue;
    panel.Dots({path->front()}, 5, start);
    break;
  }
  std::vector<LegendEntry> legend;
  if (!truth.empty()) legend.push_back({"truth", TruthStyle()});
  if (report.odometry) {
    legend.push_back({"odometry (ATE RMSE " + FormatNumber(report.odometry->error.rmse_m, 3) +
                          " m)",
                      OdometryStyle()});
  } else if (!odometry.empty()) {
    legend.push_back({report.log_only->odometry_anchored_to_estimate
                          ? "odometry (anchored to the estimate at its first pose)"
                          : "odometry (in its own frame: no POSE in its time span)",
                      OdometryStyle()});
  }
  if (report.robot) {
    legend.push_back({"estimate (ATE RMSE " + FormatNumber(report.robot->error.rmse_m, 3) + " m)",
                      EstimateStyle()});
  } else if (!estimate.empty()) {
    legend.push_back({"estimate (POSE)", EstimateStyle()});
  }
  if (report.smoothed_robot) {
    legend.push_back({"smoothed (ATE RMSE " +
                          FormatNumber(report.smoothed_robot->error.rmse_m, 3) + " m)",
                      SmoothedStyle()});
  }
  legend.push_back({"start", start, LegendMark::kDot});
  if (truth.empty() && estimate.empty() && odometry.empty()) {
    panel.Message("no ground truth, POSE or ODOMETRY in the log");
  }
  AppendLegendAndCaption(&doc, panel, legend, Subtitle(report));
  return doc.ToString();
}

}  // namespace slammtt
