// What the evaluation's pictures share (trajectory_svg.h, map_svg.h, tracks_svg.h, ...): page
// size, the styles of the truth, the odometry and the estimate, the true walls and furniture,
// and the caption. Every picture draws its panels first and appends its legend below them
// (AppendLegendAndCaption, svg_plot.h), outside the data area.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "tools/eval/evaluation.h"
#include "tools/plots/svg_plot.h"

namespace slammtt {

inline constexpr int kPictureWidthPx = 820;
inline constexpr int kMapPanelHeightPx = 684;  // a map panel, axes and title included

const LineStyle& TruthStyle();
const LineStyle& OdometryStyle();
const LineStyle& EstimateStyle();
// The smoother's trajectory (SMOOTHED_POSE), beside the filter's estimate.
const LineStyle& SmoothedStyle();
const LineStyle& MoverPathStyle();

std::vector<Eigen::Vector2d> Positions(const std::vector<TimedPose>& poses);
std::vector<Eigen::Vector2d> Points(const std::vector<IdentifiedPoint>& objects);
// Both ends of every segment (for fitting a panel's range).
std::vector<Eigen::Vector2d> SegmentEnds(const std::vector<TruthSegment>& segments);

// The true walls and furniture sides under everything else; their legend entries when any.
void DrawStaticSegments(const EvaluationReport& report, PlotPanel* panel,
                        std::vector<LegendEntry>* legend);

// The robot path a picture draws: the anchored estimate (truth frame), or without ground truth
// the POSE of the log (map frame); empty without either.
std::vector<Eigen::Vector2d> EstimatedPath(const EvaluationReport& report);
// The odometry drawn: anchored to the truth, or without ground truth to the estimate.
std::vector<Eigen::Vector2d> OdometryPath(const EvaluationReport& report);

// The name of the frame everything is drawn in, for titles.
std::string PictureFrame(const EvaluationReport& report);

// The caption's start: the log's name.
std::string Subtitle(const EvaluationReport& report);

}  // namespace slammtt
