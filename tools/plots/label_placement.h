// Placing small text labels beside points of a picture (landmark ids on the map) so that they
// do not overlap each other where that can be avoided. Pixels, y pointing down.
//
// Each label is tried, in input order, at eight positions around its point (right-above,
// right-below, left-above, left-below, right, left, above, below, at `gap_px` from the point);
// the first position whose box overlaps no label placed before it and no other point's marker
// (a square of `marker_radius_px` around each point) is taken; when none is free, the one with
// the fewest overlaps (the first of those). Deterministic: same input, same places.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace slammtt {

struct LabelBox {
  double left_px = 0.0;
  double top_px = 0.0;
  double right_px = 0.0;
  double bottom_px = 0.0;
  // Open boxes: touching edges do not overlap.
  bool Overlaps(const LabelBox& other) const;
};

struct PlacedLabel {
  Eigen::Vector2d corner_px = Eigen::Vector2d::Zero();  // lower-left corner of the text
  LabelBox box;
};

// One PlacedLabel per point (points and texts of equal size; std::invalid_argument otherwise).
// A text is taken to be TextWidthPx(text, size_px) wide (svg_plot.h) and size_px high.
std::vector<PlacedLabel> PlaceLabels(const std::vector<Eigen::Vector2d>& points_px,
                                     const std::vector<std::string>& texts, int size_px,
                                     double marker_radius_px, double gap_px = 2.0);

// Pairs of labels whose boxes overlap.
int CountLabelOverlaps(const std::vector<PlacedLabel>& labels);

}  // namespace slammtt
