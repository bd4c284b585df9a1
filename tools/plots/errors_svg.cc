#include "tools/plots/errors_svg.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "tools/plots/picture_style.h"

namespace slammtt {
namespace {

constexpr int kWidthPx = 900;
constexpr double kPanelHeightPx = 320.0;

const LineStyle kOspaStyle{"#2ca02c", 1.3, "", 1.0, "ospa"};
const LineStyle kGospaStyle{"#9467bd", 1.1, "", 0.8, "gospa"};

}  // namespace

bool NothingToTrack(const TrackingScan& scan) {
  return scan.num_truth == 0 && scan.num_tracks - scan.num_dont_care == 0;
}

std::string ErrorsSvg(const EvaluationReport& report) {
  SvgDocument doc(kWidthPx, static_cast<int>(2 * kPanelHeightPx));
  const double t0 = static_cast<double>(report.first_utime);
  auto seconds = [&](int64_t utime) { return (static_cast<double>(utime) - t0) * 1e-6; };
  const double t_end = std::max(seconds(report.last_utime), 1e-3);

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
  std::vector<LegendEntry> top_legend;
  if (report.odometry) top_legend.push_back({"odometry", OdometryStyle()});
  if (report.robot) top_legend.push_back({"estimate", EstimateStyle()});

  PlotPanel top(&doc, 0, 0, kWidthPx, kPanelHeightPx);
  double top_max = 0.1;
  for (const auto* series : {&estimate, &odometry}) {
    for (const Eigen::Vector2d& p : *series) top_max = std::max(top_max, p.y());
  }
  top.SetRange(0.0, t_end, 0.0, 1.08 * top_max, false);
  top.DrawAxes("Robot position error", "time [s]", "error [m]");
  top.Polyline(odometry, OdometryStyle(), 2000);
  top.Polyline(estimate, EstimateStyle(), 2000);
  if (report.log_only) {
    top.Message("no ground truth in the log: no position error");
  } else if (!report.robot && !report.odometry) {
    top.Message("no estimate and no odometry in the log");
  }
  const double top_legend_px = LegendBlockHeightPx(top_legend, kWidthPx);
  DrawLegendBlock(&doc, top_legend, 0, top.bottom_px(), kWidthPx);

  PlotPanel bottom(&doc, 0, top.bottom_px() + top_legend_px, kWidthPx, kPanelHeightPx);
  std::vector<Eigen::Vector2d> ospa;
  std::vector<Eigen::Vector2d> gospa;
  int64_t gap_scans = 0;
  double bottom_max = report.options.ospa_cutoff_m;
  if (report.tracking) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const TrackingScan& s : report.tracking->scans) {
      const bool gap = NothingToTrack(s);
      gap_scans += gap ? 1 : 0;
      ospa.emplace_back(seconds(s.utime), gap ? nan : s.ospa_m);
      gospa.emplace_back(seconds(s.utime), gap ? nan : s.gospa_m);
      bottom_max = std::max(bottom_max, s.gospa_m);
    }
  }
  bottom.SetRange(0.0, t_end, 0.0, 1.08 * bottom_max, false);
  bottom.DrawAxes("Tracking error per scan (c = " + FormatNumber(report.options.ospa_cutoff_m, 1) +
                      " m, p = " + FormatNumber(report.options.ospa_order, 0) +
                      "; gaps: nothing to track)",
                  "time [s]", "distance [m]");
  bottom.Polyline(gospa, kGospaStyle, 2000);
  bottom.Polyline(ospa, kOspaStyle, 2000);
  std::vector<LegendEntry> bottom_legend;
  std::string caption = Subtitle(report);
  if (report.tracking) {
    bottom_legend = {
        {"OSPA (mean " + FormatNumber(report.tracking->ospa_mean_m, 3) + " m)", kOspaStyle},
        {"GOSPA (mean " + FormatNumber(report.tracking->gospa_mean_m, 3) + " m)", kGospaStyle}};
    caption += ": " + std::to_string(gap_scans) + " of " +
               std::to_string(report.tracking->scans.size()) +
               " scored scans with no true mover and no track (gaps; counted as 0 in the means)";
  } else if (report.log_only) {
    bottom.Message("no ground truth in the log: no OSPA / GOSPA");
  } else {
    bottom.Message("no TRACKS in the log");
  }
  AppendLegendAndCaption(&doc, bottom, bottom_legend, caption);
  return doc.ToString();
}

}  // namespace slammtt
