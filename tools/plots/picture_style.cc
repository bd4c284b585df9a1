#include "tools/plots/picture_style.h"

namespace slammtt {
namespace {

const LineStyle kWallStyle{"#8c6d46", 2.2, "", 0.8};
const LineStyle kFurnitureStyle{"#c9a66b", 1.6, "", 0.8};

}  // namespace

const LineStyle& TruthStyle() {
  static const LineStyle style{"#111111", 2.0, "", 1.0};
  return style;
}
const LineStyle& OdometryStyle() {
  static const LineStyle style{"#ff7f0e", 1.6, "7 4", 1.0};
  return style;
}
const LineStyle& EstimateStyle() {
  static const LineStyle style{"#1f77b4", 1.6, "", 1.0};
  return style;
}
const LineStyle& SmoothedStyle() {
  static const LineStyle style{"#9467bd", 1.6, "2 2", 1.0};
  return style;
}
const LineStyle& MoverPathStyle() {
  static const LineStyle style{"#9a9a9a", 5.0, "", 0.45};
  return style;
}

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

std::vector<Eigen::Vector2d> SegmentEnds(const std::vector<TruthSegment>& segments) {
  std::vector<Eigen::Vector2d> out;
  for (const TruthSegment& g : segments) {
    out.push_back(g.from_m);
    out.push_back(g.to_m);
  }
  return out;
}

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

std::vector<Eigen::Vector2d> EstimatedPath(const EvaluationReport& report) {
  if (report.robot) return Positions(report.robot->anchored);
  if (report.log_only) return Positions(report.log_only->estimate);
  return {};
}

std::vector<Eigen::Vector2d> OdometryPath(const EvaluationReport& report) {
  if (report.odometry) return Positions(report.odometry->anchored);
  if (report.log_only) return Positions(report.log_only->odometry);
  return {};
}

std::string PictureFrame(const EvaluationReport& report) {
  return report.log_only ? "estimator's map frame, no ground truth" : "truth frame";
}

std::string Subtitle(const EvaluationReport& report) { return report.source; }

}  // namespace slammtt
