#include "tools/plots/label_placement.h"

#include <stdexcept>

#include "tools/plots/svg_plot.h"

namespace slammtt {

bool LabelBox::Overlaps(const LabelBox& other) const {
  return left_px < other.right_px && other.left_px < right_px && top_px < other.bottom_px &&
         other.top_px < bottom_px;
}

std::vector<PlacedLabel> PlaceLabels(const std::vector<Eigen::Vector2d>& points_px,
                                     const std::vector<std::string>& texts, int size_px,
                                     double marker_radius_px, double gap_px) {
  if (points_px.size() != texts.size()) {
    throw std::invalid_argument("PlaceLabels: one text per point");
  }
  std::vector<LabelBox> markers;
  for (const Eigen::Vector2d& p : points_px) {
    markers.push_back({p.x() - marker_radius_px, p.y() - marker_radius_px,
                       p.x() + marker_radius_px, p.y() + marker_radius_px});
  }
  std::vector<PlacedLabel> placed;
  for (size_t k = 0; k < points_px.size(); ++k) {
    const double w = TextWidthPx(texts[k], size_px);
    const double h = size_px;
    const double x = points_px[k].x();
    const double y = points_px[k].y();
    const double d = marker_radius_px + gap_px;
    // Lower-left corners of the candidate boxes, in the order of the header.
    const Eigen::Vector2d candidates[] = {
        {x + d, y - d},          {x + d, y + d + h},     {x - d - w, y - d},
        {x - d - w, y + d + h},  {x + d, y + 0.5 * h},   {x - d - w, y + 0.5 * h},
        {x - 0.5 * w, y - d},    {x - 0.5 * w, y + d + h}};
    PlacedLabel best;
    int best_overlaps = -1;
    for (const Eigen::Vector2d& c : candidates) {
      const LabelBox box{c.x(), c.y() - h, c.x() + w, c.y()};
      int overlaps = 0;
      for (const PlacedLabel& other : placed) overlaps += box.Overlaps(other.box) ? 1 : 0;
      for (size_t m = 0; m < markers.size(); ++m) {
        overlaps += m != k && box.Overlaps(markers[m]) ? 1 : 0;
      }
      if (best_overlaps < 0 || overlaps < best_overlaps) {
        best = PlacedLabel{c, box};
        best_overlaps = overlaps;
      }
      if (overlaps == 0) break;
    }
    placed.push_back(best);
  }
  return placed;
}

int CountLabelOverlaps(const std::vector<PlacedLabel>& labels) {
  int n = 0;
  for (size_t a = 0; a < labels.size(); ++a) {
    for (size_t b = a + 1; b < labels.size(); ++b) n += labels[a].box.Overlaps(labels[b].box);
  }
  return n;
}

}  // namespace slammtt
