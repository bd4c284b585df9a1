#include "tools/plots/svg_plot.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace slammtt {
namespace {

constexpr double kAxisLeftPx = 58.0;
constexpr double kAxisBottomPx = 42.0;
constexpr double kTitlePx = 26.0;
constexpr double kRightPx = 14.0;

std::string RoleAttribute(const LineStyle& style) {
  return style.role.empty() ? "" : " class=\"" + style.role + "\"";
}

std::string StrokeAttributes(const LineStyle& style) {
  std::string s = "stroke=\"" + style.colour + "\" stroke-width=\"" +
                  FormatNumber(style.width_px, 2) + "\"";
  if (!style.dash.empty()) s += " stroke-dasharray=\"" + style.dash + "\"";
  if (style.opacity < 1.0) s += " stroke-opacity=\"" + FormatNumber(style.opacity, 2) + "\"";
  return s + RoleAttribute(style);
}

// The legend mark of one entry, centred vertically on `cy`, from x to x + 22.
std::string LegendMarkElement(const LegendEntry& e, double x, double cy) {
  LineStyle style = e.style;
  style.role.clear();  // a legend mark is not data of its role
  if (e.mark == LegendMark::kDot) {
    return "<circle cx=\"" + FormatNumber(x + 11, 1) + "\" cy=\"" + FormatNumber(cy, 1) +
           "\" r=\"3.5\" fill=\"" + style.colour + "\"/>";
  }
  if (e.mark == LegendMark::kTriangle) {
    return "<path d=\"M" + FormatNumber(x + 6.5, 1) + " " + FormatNumber(cy - 4.5, 1) + "L" +
           FormatNumber(x + 15.5, 1) + " " + FormatNumber(cy - 4.5, 1) + "L" +
           FormatNumber(x + 11, 1) + " " + FormatNumber(cy + 4.5, 1) + "Z\" fill=\"" +
           style.colour + "\" stroke=\"none\"/>";
  }
  if (e.mark == LegendMark::kDiamond) {
    return "<path d=\"M" + FormatNumber(x + 11, 1) + " " + FormatNumber(cy - 4.5, 1) + "L" +
           FormatNumber(x + 15.5, 1) + " " + FormatNumber(cy, 1) + "L" + FormatNumber(x + 11, 1) +
           " " + FormatNumber(cy + 4.5, 1) + "L" + FormatNumber(x + 6.5, 1) + " " +
           FormatNumber(cy, 1) + "Z\" fill=\"" + style.colour + "\" stroke=\"none\"/>";
  }
  if (e.mark == LegendMark::kCross) {
    return "<path d=\"M" + FormatNumber(x + 6, 1) + " " + FormatNumber(cy, 1) + "H" +
           FormatNumber(x + 16, 1) + "M" + FormatNumber(x + 11, 1) + " " +
           FormatNumber(cy - 5, 1) + "V" + FormatNumber(cy + 5, 1) + "\" " +
           StrokeAttributes(style) + "/>";
  }
  return "<line x1=\"" + FormatNumber(x, 1) + "\" y1=\"" + FormatNumber(cy, 1) + "\" x2=\"" +
         FormatNumber(x + 22, 1) + "\" y2=\"" + FormatNumber(cy, 1) + "\" " +
         StrokeAttributes(style) + "/>";
}

constexpr double kLegendRowPx = 16.0;
constexpr double kLegendPaddingPx = 6.0;
constexpr double kLegendLeftPx = 58.0;  // under the panel's inner box, as the axis
constexpr int kLegendTextPx = 11;

double LegendColumnWidthPx(const std::vector<LegendEntry>& entries) {
  double widest = 0.0;
  for (const LegendEntry& e : entries) widest = std::max(widest, TextWidthPx(e.label, 11));
  return 28.0 + widest + 16.0;
}

int LegendColumns(const std::vector<LegendEntry>& entries, double width_px) {
  const double usable = width_px - kLegendLeftPx - 14.0;
  const int fit = static_cast<int>(std::floor(usable / LegendColumnWidthPx(entries)));
  return std::max(1, std::min(fit, static_cast<int>(entries.size())));
}

}  // namespace

std::string FormatNumber(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  std::string s = text;
  if (s == "-0" || s.find_first_not_of("-0.") == std::string::npos) {
    // "-0.00" and "0.00" alike print as 0 with the same decimals
    std::snprintf(text, sizeof(text), "%.*f", decimals, 0.0);
    s = text;
  }
  return s;
}

std::vector<double> NiceTicks(double min, double max, int target_count) {
  std::vector<double> ticks;
  if (!(max > min) || !std::isfinite(min) || !std::isfinite(max) || target_count < 1) return ticks;
  const double raw = (max - min) / target_count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  const double first = std::ceil(min / step - 1e-9) * step;
  for (double t = first; t <= max + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
    if (ticks.size() > 100) break;
  }
  return ticks;
}

int TickDecimals(const std::vector<double>& ticks) {
  if (ticks.size() < 2) return 0;
  const double step = ticks[1] - ticks[0];
  // A step of 1, 2 or 5 times 10^k needs max(0, -k) decimals.
  return std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
}

std::string IdentityColour(int64_t id) {
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#17becf", "#8c564b", "#e377c2",
                                  "#bcbd22", "#393b79", "#637939", "#843c39"};
  const int64_t n = static_cast<int64_t>(sizeof(palette) / sizeof(palette[0]));
  return palette[((id % n) + n) % n];
}

std::string EscapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

SvgDocument::SvgDocument(int width_px, int height_px)
    : width_px_(width_px), height_px_(height_px) {}

void SvgDocument::Add(const std::string& element) { elements_.push_back(element); }

void SvgDocument::Text(double x_px, double y_px, const std::string& text, int size_px,
                       const std::string& anchor, const std::string& extra) {
  Add("<text x=\"" + FormatNumber(x_px, 1) + "\" y=\"" + FormatNumber(y_px, 1) +
      "\" font-size=\"" + std::to_string(size_px) + "\" text-anchor=\"" + anchor + "\"" +
      (extra.empty() ? "" : " " + extra) + ">" + EscapeXml(text) + "</text>");
}

std::string SvgDocument::ToString() const {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width_px_
      << "\" height=\"" << height_px_ << "\" viewBox=\"0 0 " << width_px_ << " " << height_px_
      << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << width_px_ << "\" height=\"" << height_px_
      << "\" fill=\"#ffffff\"/>\n";
  for (const std::string& e : elements_) out << e << "\n";
  out << "</svg>\n";
  return out.str();
}

PlotPanel::PlotPanel(SvgDocument* document, double left_px, double top_px, double width_px,
                     double height_px)
    : document_(document),
      left_px_(left_px),
      top_px_(top_px),
      width_px_(width_px),
      height_px_(height_px),
      inner_left_px_(left_px + kAxisLeftPx),
      inner_top_px_(top_px + kTitlePx),
      inner_width_px_(width_px - kAxisLeftPx - kRightPx),
      inner_height_px_(height_px - kAxisBottomPx - kTitlePx) {
  const std::string id = document_->NextId();
  document_->Add("<clipPath id=\"" + id + "\"><rect x=\"" + FormatNumber(inner_left_px_, 1) +
                 "\" y=\"" + FormatNumber(inner_top_px_, 1) + "\" width=\"" +
                 FormatNumber(inner_width_px_, 1) + "\" height=\"" +
                 FormatNumber(inner_height_px_, 1) + "\"/></clipPath>");
  clip_attribute_ = "clip-path=\"url(#" + id + ")\"";
}

void PlotPanel::SetRange(double x_min, double x_max, double y_min, double y_max,
                         bool equal_aspect) {
  auto widen = [](double* lo, double* hi) {
    if (!std::isfinite(*lo) || !std::isfinite(*hi)) {
      *lo = 0.0;
      *hi = 1.0;
    }
    if (*hi - *lo < 1e-9) {
      *lo -= 0.5;
      *hi += 0.5;
    }
  };
  widen(&x_min, &x_max);
  widen(&y_min, &y_max);
  if (equal_aspect) {
    const double scale = std::max((x_max - x_min) / inner_width_px_,
                                  (y_max - y_min) / inner_height_px_);
    const double cx = 0.5 * (x_min + x_max);
    const double cy = 0.5 * (y_min + y_max);
    x_min = cx - 0.5 * scale * inner_width_px_;
    x_max = cx + 0.5 * scale * inner_width_px_;
    y_min = cy - 0.5 * scale * inner_height_px_;
    y_max = cy + 0.5 * scale * inner_height_px_;
  }
  x_min_ = x_min;
  x_max_ = x_max;
  y_min_ = y_min;
  y_max_ = y_max;
}

void PlotPanel::FitRange(const std::vector<std::vector<Eigen::Vector2d>>& point_sets,
                         bool equal_aspect) {
  double x_min = std::numeric_limits<double>::infinity();
  double y_min = x_min;
  double x_max = -x_min;
  double y_max = -x_min;
  for (const auto& set : point_sets) {
    for (const Eigen::Vector2d& p : set) {
      if (!p.allFinite()) continue;
      x_min = std::min(x_min, p.x());
      x_max = std::max(x_max, p.x());
      y_min = std::min(y_min, p.y());
      y_max = std::max(y_max, p.y());
    }
  }
  if (x_min > x_max) {
    SetRange(0, 1, 0, 1, equal_aspect);
    return;
  }
  const double mx = 0.05 * std::max(x_max - x_min, 1e-6);
  const double my = 0.05 * std::max(y_max - y_min, 1e-6);
  SetRange(x_min - mx, x_max + mx, y_min - my, y_max + my, equal_aspect);
}

Eigen::Vector2d PlotPanel::ToPixel(const Eigen::Vector2d& data) const {
  return Eigen::Vector2d(
      inner_left_px_ + (data.x() - x_min_) / (x_max_ - x_min_) * inner_width_px_,
      inner_top_px_ + (y_max_ - data.y()) / (y_max_ - y_min_) * inner_height_px_);
}

void PlotPanel::DrawAxes(const std::string& title, const std::string& x_label,
                         const std::string& y_label) {
  SvgDocument& d = *document_;
  const double right = inner_left_px_ + inner_width_px_;
  const double bottom = inner_top_px_ + inner_height_px_;
  const std::vector<double> x_ticks = NiceTicks(x_min_, x_max_, 8);
  for (double t : x_ticks) {
    const double x = ToPixel(Eigen::Vector2d(t, y_min_)).x();
    d.Add("<line x1=\"" + FormatNumber(x, 1) + "\" y1=\"" + FormatNumber(inner_top_px_, 1) +
          "\" x2=\"" + FormatNumber(x, 1) + "\" y2=\"" + FormatNumber(bottom, 1) +
          "\" stroke=\"#e4e4e4\" stroke-width=\"1\"/>");
    d.Text(x, bottom + 15, FormatNumber(t, TickDecimals(x_ticks)), 11, "middle");
  }
  std::vector<std::pair<double, std::string>> y_labels = y_tick_labels_;
  if (y_labels.empty()) {
    const std::vector<double> y_ticks = NiceTicks(y_min_, y_max_, 6);
    for (double t : y_ticks) y_labels.emplace_back(t, FormatNumber(t, TickDecimals(y_ticks)));
  }
  for (const auto& [t, text] : y_labels) {
    const double y = ToPixel(Eigen::Vector2d(x_min_, t)).y();
    d.Add("<line x1=\"" + FormatNumber(inner_left_px_, 1) + "\" y1=\"" + FormatNumber(y, 1) +
          "\" x2=\"" + FormatNumber(right, 1) + "\" y2=\"" + FormatNumber(y, 1) +
          "\" stroke=\"#e4e4e4\" stroke-width=\"1\"/>");
    d.Text(inner_left_px_ - 6, y + 4, text, 11, "end");
  }
  d.Add("<rect x=\"" + FormatNumber(inner_left_px_, 1) + "\" y=\"" +
        FormatNumber(inner_top_px_, 1) + "\" width=\"" + FormatNumber(inner_width_px_, 1) +
        "\" height=\"" + FormatNumber(inner_height_px_, 1) +
        "\" fill=\"none\" stroke=\"#444444\" stroke-width=\"1\"/>");
  d.Text(left_px_ + 0.5 * width_px_, top_px_ + 17, title, 14, "middle", "font-weight=\"bold\"");
  d.Text(inner_left_px_ + 0.5 * inner_width_px_, bottom + 33, x_label, 12, "middle");
  const double ly = inner_top_px_ + 0.5 * inner_height_px_;
  const double lx = left_px_ + 14;
  d.Text(lx, ly, y_label, 12, "middle",
         "transform=\"rotate(-90 " + FormatNumber(lx, 1) + " " + FormatNumber(ly, 1) + ")\"");
}

void PlotPanel::Polyline(const std::vector<Eigen::Vector2d>& points, const LineStyle& style,
                         size_t max_points) {
  const size_t step = std::max<size_t>(1, (points.size() + max_points - 1) /
                                              std::max<size_t>(1, max_points));
  std::string path;
  std::vector<Eigen::Vector2d> lone_points;
  // Each run of finite points is one subpath, decimated to every step-th point plus its last.
  size_t k = 0;
  while (k < points.size()) {
    if (!points[k].allFinite()) {
      ++k;
      continue;
    }
    size_t end = k;
    while (end < points.size() && points[end].allFinite()) ++end;
    if (end - k == 1) {
      lone_points.push_back(points[k]);
    } else {
      for (size_t i = k;; i = std::min(i + step, end - 1)) {
        const Eigen::Vector2d p = ToPixel(points[i]);
        path += (i == k ? "M" : "L") + FormatNumber(p.x(), 1) + " " + FormatNumber(p.y(), 1);
        if (i == end - 1) break;
      }
    }
    k = end;
  }
  if (!path.empty()) {
    document_->Add("<path d=\"" + path + "\" fill=\"none\" " + StrokeAttributes(style) +
                   " stroke-linejoin=\"round\" " + clip_attribute_ + "/>");
  }
  if (!lone_points.empty() && points.size() > 1) {
    Dots(lone_points, std::max(1.0, style.width_px), style);
  }
}

void PlotPanel::Dots(const std::vector<Eigen::Vector2d>& points, double radius_px,
                     const LineStyle& style, bool filled) {
  for (const Eigen::Vector2d& point : points) {
    if (!point.allFinite()) continue;
    const Eigen::Vector2d p = ToPixel(point);
    document_->Add("<circle cx=\"" + FormatNumber(p.x(), 1) + "\" cy=\"" +
                   FormatNumber(p.y(), 1) + "\" r=\"" + FormatNumber(radius_px, 1) + "\" " +
                   (filled ? "fill=\"" + style.colour + "\" stroke=\"none\""
                           : "fill=\"none\" " + StrokeAttributes(style)) +
                   (style.opacity < 1.0 && filled
                        ? " fill-opacity=\"" + FormatNumber(style.opacity, 2) + "\""
                        : "") +
                   (filled ? RoleAttribute(style) : "") + " " + clip_attribute_ + "/>");
  }
}

void PlotPanel::Crosses(const std::vector<Eigen::Vector2d>& points, double half_size_px,
                        const LineStyle& style) {
  for (const Eigen::Vector2d& point : points) {
    if (!point.allFinite()) continue;
    const Eigen::Vector2d p = ToPixel(point);
    const std::string x0 = FormatNumber(p.x() - half_size_px, 1);
    const std::string x1 = FormatNumber(p.x() + half_size_px, 1);
    const std::string y0 = FormatNumber(p.y() - half_size_px, 1);
    const std::string y1 = FormatNumber(p.y() + half_size_px, 1);
    document_->Add("<path d=\"M" + x0 + " " + FormatNumber(p.y(), 1) + "H" + x1 + "M" +
                   FormatNumber(p.x(), 1) + " " + y0 + "V" + y1 + "\" " +
                   StrokeAttributes(style) + " " + clip_attribute_ + "/>");
  }
}

void PlotPanel::FilledMarkers(const std::vector<Eigen::Vector2d>& points,
                              const std::vector<Eigen::Vector2d>& corners, double half_size_px,
                              const LineStyle& style) {
  for (const Eigen::Vector2d& point : points) {
    if (!point.allFinite()) continue;
    const Eigen::Vector2d p = ToPixel(point);
    std::string path;
    for (const Eigen::Vector2d& c : corners) {
      const Eigen::Vector2d q = p + half_size_px * c;
      path += (path.empty() ? "M" : "L") + FormatNumber(q.x(), 1) + " " + FormatNumber(q.y(), 1);
    }
    document_->Add("<path d=\"" + path + "Z\" fill=\"" + style.colour + "\" stroke=\"none\"" +
                   RoleAttribute(style) + " " + clip_attribute_ + "/>");
  }
}

void PlotPanel::Triangles(const std::vector<Eigen::Vector2d>& points, double half_size_px,
                          const LineStyle& style) {
  FilledMarkers(points, {{-1, -1}, {1, -1}, {0, 1}}, half_size_px, style);
}

void PlotPanel::Diamonds(const std::vector<Eigen::Vector2d>& points, double half_size_px,
                         const LineStyle& style) {
  FilledMarkers(points, {{0, -1}, {1, 0}, {0, 1}, {-1, 0}}, half_size_px, style);
}

void PlotPanel::Box(const Eigen::Vector2d& corner_a, const Eigen::Vector2d& corner_b,
                    const LineStyle& style) {
  if (!corner_a.allFinite() || !corner_b.allFinite()) return;
  const Eigen::Vector2d a = ToPixel(corner_a);
  const Eigen::Vector2d b = ToPixel(corner_b);
  const Eigen::Vector2d low = a.cwiseMin(b);
  const Eigen::Vector2d size = (a - b).cwiseAbs();
  document_->Add("<rect x=\"" + FormatNumber(low.x(), 1) + "\" y=\"" + FormatNumber(low.y(), 1) +
                 "\" width=\"" + FormatNumber(std::max(size.x(), 0.5), 1) + "\" height=\"" +
                 FormatNumber(std::max(size.y(), 0.5), 1) + "\" fill=\"" + style.colour +
                 "\" stroke=\"none\"" + RoleAttribute(style) + " " + clip_attribute_ + "/>");
}

void PlotPanel::CovarianceEllipse(const Eigen::Vector2d& centre, const Eigen::Matrix2d& covariance,
                                  double sigma, const LineStyle& style) {
  if (!centre.allFinite() || !covariance.allFinite()) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(
      0.5 * (covariance + covariance.transpose()));
  const Eigen::Vector2d values = solver.eigenvalues().cwiseMax(0.0);
  const Eigen::Vector2d major = solver.eigenvectors().col(1);
  const double scale_x = inner_width_px_ / (x_max_ - x_min_);
  const double scale_y = inner_height_px_ / (y_max_ - y_min_);
  // In pixels the y axis points down: the angle changes sign. (Equal-aspect panels only, so
  // one scale serves both radii.)
  const double rx = std::max(0.5, sigma * std::sqrt(values(1)) * scale_x);
  const double ry = std::max(0.5, sigma * std::sqrt(values(0)) * scale_y);
  const double angle_deg = -std::atan2(major.y(), major.x()) * 180.0 / M_PI;
  const Eigen::Vector2d c = ToPixel(centre);
  document_->Add("<ellipse cx=\"" + FormatNumber(c.x(), 1) + "\" cy=\"" + FormatNumber(c.y(), 1) +
                 "\" rx=\"" + FormatNumber(rx, 1) + "\" ry=\"" + FormatNumber(ry, 1) +
                 "\" transform=\"rotate(" + FormatNumber(angle_deg, 1) + " " +
                 FormatNumber(c.x(), 1) + " " + FormatNumber(c.y(), 1) + ")\" fill=\"none\" " +
                 StrokeAttributes(style) + " " + clip_attribute_ + "/>");
}

void PlotPanel::Label(const Eigen::Vector2d& at, const std::string& text,
                      const std::string& colour) {
  if (!at.allFinite()) return;
  const Eigen::Vector2d p = ToPixel(at);
  document_->Text(p.x() + 4, p.y() - 4, text, 10, "start",
                  "fill=\"" + colour + "\" " + clip_attribute_);
}

void PlotPanel::LabelAtPixel(const Eigen::Vector2d& corner_px, const std::string& text,
                             int size_px, const std::string& colour) {
  document_->Text(corner_px.x(), corner_px.y(), text, size_px, "start",
                  "fill=\"" + colour + "\" " + clip_attribute_);
}

void PlotPanel::Message(const std::string& text) {
  document_->Text(inner_left_px_ + 0.5 * inner_width_px_, inner_top_px_ + 0.5 * inner_height_px_,
                  text, 13, "middle", "fill=\"#888888\"");
}

double TextWidthPx(const std::string& text, int size_px) {
  return 0.62 * size_px * static_cast<double>(text.size());
}

double LegendBlockHeightPx(const std::vector<LegendEntry>& entries, double width_px) {
  if (entries.empty()) return 0.0;
  const int columns = LegendColumns(entries, width_px);
  const size_t rows = (entries.size() + columns - 1) / columns;
  return kLegendRowPx * static_cast<double>(rows) + 2 * kLegendPaddingPx + 4.0;
}

void DrawLegendBlock(SvgDocument* document, const std::vector<LegendEntry>& entries,
                     double left_px, double top_px, double width_px) {
  if (entries.empty()) return;
  const int columns = LegendColumns(entries, width_px);
  const double column_width = LegendColumnWidthPx(entries);
  const size_t rows = (entries.size() + columns - 1) / columns;
  const double x0 = left_px + kLegendLeftPx;
  const double y0 = top_px + 4.0;
  document->Add("<g class=\"legend\">");
  document->Add("<rect x=\"" + FormatNumber(x0 - 4, 1) + "\" y=\"" + FormatNumber(y0, 1) +
                "\" width=\"" + FormatNumber(column_width * columns, 1) + "\" height=\"" +
                FormatNumber(kLegendRowPx * static_cast<double>(rows) + 2 * kLegendPaddingPx, 1) +
                "\" fill=\"#ffffff\" stroke=\"#bbbbbb\"/>");
  for (size_t k = 0; k < entries.size(); ++k) {
    // Filled row by row, left to right.
    const double x = x0 + column_width * static_cast<double>(k % columns);
    const double cy = y0 + kLegendPaddingPx + kLegendRowPx * static_cast<double>(k / columns) + 7;
    document->Add(LegendMarkElement(entries[k], x, cy));
    document->Text(x + 28, cy + 4, entries[k].label, kLegendTextPx);
  }
  document->Add("</g>");
}

double AppendLegendAndCaption(SvgDocument* document, const PlotPanel& panel,
                              const std::vector<LegendEntry>& entries,
                              const std::string& caption) {
  double y = panel.bottom_px();
  DrawLegendBlock(document, entries, panel.left_px(), y, panel.width_px());
  y += LegendBlockHeightPx(entries, panel.width_px());
  if (!caption.empty()) {
    document->Text(panel.left_px() + 0.5 * panel.width_px(), y + 14, caption, 10, "middle",
                   "fill=\"#777777\"");
    y += 20;
  }
  document->set_height_px(static_cast<int>(std::ceil(y)));
  return document->height_px();
}

}  // namespace slammtt
