// A small SVG builder for the evaluation's pictures (text only; writing files is the caller's): a
// document of fixed pixel width holding plot panels, each mapping data coordinates (metres,
// seconds) to pixels with axes, ticks and a grid, and legends laid out outside every panel's data
// area (DrawLegendBlock, AppendLegendAndCaption), so that a legend never covers data. Every
// data element is clipped to its panel's inner box and carries that clip-path attribute; legends
// are <g class="legend"> groups framed by one rect. Numbers are written with a fixed number of decimals, so the same data gives
// the same bytes, and long polylines are decimated to keep files small (never across a gap).
// Only the SVG 1.1 basics every browser and image viewer renders (path, circle, ellipse, line,
// rect, text, g).
#pragma once

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace slammtt {

struct LineStyle {
  LineStyle(std::string colour_ = "#000000", double width_px_ = 1.5, std::string dash_ = "",
            double opacity_ = 1.0, std::string role_ = "")
      : colour(std::move(colour_)), width_px(width_px_), dash(std::move(dash_)),
        opacity(opacity_), role(std::move(role_)) {}
  std::string colour;
  double width_px;
  std::string dash;  // SVG stroke-dasharray, e.g. "6 3"; empty for solid
  double opacity;
  // Written as class="role" on what is drawn with it (empty: no class), so that a reader of the
  // SVG (a test) can tell one series or marker kind from another.
  std::string role;
};

// How a legend entry shows its style: as the line, the dot, the cross, the triangle or the
// diamond drawn in the panel.
enum class LegendMark { kLine, kDot, kCross, kTriangle, kDiamond };

struct LegendEntry {
  std::string label;
  LineStyle style;
  LegendMark mark = LegendMark::kLine;
};

class SvgDocument {
 public:
  SvgDocument(int width_px, int height_px);
  // Raw elements in pixel coordinates; `attributes` is added verbatim.
  void Add(const std::string& element);
  void Text(double x_px, double y_px, const std::string& text, int size_px = 12,
            const std::string& anchor = "start", const std::string& extra = "");
  std::string ToString() const;

  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  // The height grows when a legend block or a caption is appended below the panels.
  void set_height_px(int height_px) { height_px_ = height_px; }
  // A fresh element id ("c1", "c2", ...), for clip paths.
  std::string NextId() { return "c" + std::to_string(++ids_); }

 private:
  int width_px_;
  int height_px_;
  int ids_ = 0;
  std::vector<std::string> elements_;
};

// One plot area of a document. Data drawn into it is clipped to its inner box.
class PlotPanel {
 public:
  // The panel covers the pixel box (left, top, width, height) of `document`, axes included.
  PlotPanel(SvgDocument* document, double left_px, double top_px, double width_px,
            double height_px);

  // Data ranges. With `equal_aspect` one metre is the same length on both axes (maps); the
  // ranges are widened to fill the panel. Call before drawing; empty or degenerate ranges are
  // widened to a unit around their value.
  void SetRange(double x_min, double x_max, double y_min, double y_max, bool equal_aspect);
  // Fits the range to every point given (plus a margin of 5 %).
  void FitRange(const std::vector<std::vector<Eigen::Vector2d>>& point_sets, bool equal_aspect);

  void DrawAxes(const std::string& title, const std::string& x_label, const std::string& y_label);
  // A non-finite point is a gap: the line stops before it and starts again after it (also when
  // the line is decimated to about `max_points`). A point alone between gaps is drawn as a dot
  // of the line's width.
  void Polyline(const std::vector<Eigen::Vector2d>& points, const LineStyle& style,
                size_t max_points = 1500);
  void Dots(const std::vector<Eigen::Vector2d>& points, double radius_px, const LineStyle& style,
            bool filled = true);
  void Crosses(const std::vector<Eigen::Vector2d>& points, double half_size_px,
               const LineStyle& style);
  // Filled markers: a triangle pointing down, a diamond, centred on each point.
  void Triangles(const std::vector<Eigen::Vector2d>& points, double half_size_px,
                 const LineStyle& style);
  void Diamonds(const std::vector<Eigen::Vector2d>& points, double half_size_px,
                const LineStyle& style);
  // A filled rectangle between two data corners (style.colour is the fill).
  void Box(const Eigen::Vector2d& corner_a, const Eigen::Vector2d& corner_b,
           const LineStyle& style);
  // Labels for the y axis at given data values instead of numeric ticks (the rows of a
  // timeline). Call before DrawAxes.
  void SetYTickLabels(std::vector<std::pair<double, std::string>> labels) {
    y_tick_labels_ = std::move(labels);
  }
  // The ellipse {x : (x - centre)^T C^-1 (x - centre) = sigma^2} of a 2x2 covariance.
  void CovarianceEllipse(const Eigen::Vector2d& centre, const Eigen::Matrix2d& covariance,
                         double sigma, const LineStyle& style);
  // A small text next to a data point (clipped to the panel like the data).
  void Label(const Eigen::Vector2d& at, const std::string& text, const std::string& colour);
  // A text whose lower-left corner is at pixel `corner_px` (clipped like the data).
  void LabelAtPixel(const Eigen::Vector2d& corner_px, const std::string& text, int size_px,
                    const std::string& colour);
  // A centred message inside the panel ("no estimator output").
  void Message(const std::string& text);

  Eigen::Vector2d ToPixel(const Eigen::Vector2d& data) const;
  // The panel's bottom edge in document pixels (below the axis labels): where a legend block
  // under it starts.
  double bottom_px() const { return top_px_ + height_px_; }
  double left_px() const { return left_px_; }
  double width_px() const { return width_px_; }

 private:
  SvgDocument* document_;
  double left_px_;
  double top_px_;
  double width_px_;
  double height_px_;
  // Inner plotting box (inside the axes).
  double inner_left_px_;
  double inner_top_px_;
  double inner_width_px_;
  double inner_height_px_;
  double x_min_ = 0.0;
  double x_max_ = 1.0;
  double y_min_ = 0.0;
  double y_max_ = 1.0;
  std::string clip_attribute_;  // clip-path="url(#...)" of the inner box
  std::vector<std::pair<double, std::string>> y_tick_labels_;

  // A filled polygon with the corners `corners` (in units of half_size_px, y down) at each point.
  void FilledMarkers(const std::vector<Eigen::Vector2d>& points,
                     const std::vector<Eigen::Vector2d>& corners, double half_size_px,
                     const LineStyle& style);
};

// A legend outside the data area: its entries in rows of as many equal columns as the longest
// label allows within `width_px` (at least one), framed by a box. LegendBlockHeightPx is the
// height it takes, DrawLegendBlock draws it with its top-left corner at (left_px, top_px).
double LegendBlockHeightPx(const std::vector<LegendEntry>& entries, double width_px);
void DrawLegendBlock(SvgDocument* document, const std::vector<LegendEntry>& entries,
                     double left_px, double top_px, double width_px);
// Appends `entries` as a legend block below `panel` (from its bottom edge, across its width) and
// then a one-line grey caption (none when empty); the document ends below them (its height is
// set to that). Returns the new height.
double AppendLegendAndCaption(SvgDocument* document, const PlotPanel& panel,
                              const std::vector<LegendEntry>& entries,
                              const std::string& caption);
// The width in pixels a text of `size_px` is taken to need (a conservative estimate for the
// sans-serif fonts a viewer substitutes: 0.62 em per character).
double TextWidthPx(const std::string& text, int size_px);

// "%.Nf" formatting used for every coordinate.
std::string FormatNumber(double value, int decimals);
// Ticks at 1, 2 or 5 times a power of ten, about `target_count` of them, within [min, max].
std::vector<double> NiceTicks(double min, double max, int target_count);
// Decimals that print every tick of NiceTicks() alike and exactly (0 for steps >= 1, 1 for 0.5 or
// 0.2 or 0.1, ...): "0.0 0.5 1.0", never "0 0.50 1".
int TickDecimals(const std::vector<double>& ticks);
// A colour for an identity (a fixed palette of 12 distinguishable colours).
std::string IdentityColour(int64_t id);
// Escapes &, <, >, " for SVG text.
std::string EscapeXml(const std::string& text);

}  // namespace slammtt
