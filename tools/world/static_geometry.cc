#include "tools/world/static_geometry.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

namespace {

constexpr double kShortestPieceM = 1e-3;

// The pieces of side a -> b left between its openings.
void AddSide(const PlanarPoint& a, const PlanarPoint& b, int side,
             const std::vector<WallOpening>& openings, const StaticSegment& prototype,
             std::vector<StaticSegment>* out) {
  const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  std::vector<std::pair<double, double>> gaps;
  for (const WallOpening& o : openings) {
    if (o.side == side) gaps.emplace_back(o.offset_m, o.offset_m + o.width_m);
  }
  std::sort(gaps.begin(), gaps.end());
  auto emit = [&](double from_m, double to_m) {
    if (to_m - from_m < kShortestPieceM) return;
    StaticSegment piece = prototype;
    const double f0 = from_m / length;
    const double f1 = to_m / length;
    piece.segment = Segment{a.x_m + f0 * (b.x_m - a.x_m), a.y_m + f0 * (b.y_m - a.y_m),
                            a.x_m + f1 * (b.x_m - a.x_m), a.y_m + f1 * (b.y_m - a.y_m)};
    if (gaps.empty()) piece.segment = Segment{a.x_m, a.y_m, b.x_m, b.y_m};  // exact ends
    out->push_back(piece);
  };
  double from = 0.0;
  for (const auto& gap : gaps) {
    emit(from, gap.first);
    from = gap.second;
  }
  emit(from, length);
}

}  // namespace

std::vector<PlanarPoint> BoxCorners(const StaticObjectSpec& spec) {
  const double c = std::cos(spec.heading_rad);
  const double s = std::sin(spec.heading_rad);
  const double hx = 0.5 * spec.size_x_m;
  const double hy = 0.5 * spec.size_y_m;
  std::vector<PlanarPoint> corners;
  for (const auto& [u, v] : {std::pair{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}}) {
    corners.push_back(PlanarPoint{spec.x_m + c * u - s * v, spec.y_m + s * u + c * v});
  }
  return corners;
}

StaticGeometry BuildStaticGeometry(const std::vector<StaticObjectSpec>& statics) {
  StaticGeometry geometry;
  for (size_t i = 0; i < statics.size(); ++i) {
    const StaticObjectSpec& spec = statics[i];
    const int index = static_cast<int>(i);
    switch (spec.shape) {
      case StaticShape::kCircle:
        geometry.circles.push_back(
            StaticCircle{Circle{spec.x_m, spec.y_m, spec.radius_m}, spec.id, spec.kind, index});
        break;
      case StaticShape::kLegs: {
        StaticObjectSpec inner = spec;
        inner.size_x_m -= 2.0 * spec.leg_radius_m;
        inner.size_y_m -= 2.0 * spec.leg_radius_m;
        const std::vector<PlanarPoint> corners = BoxCorners(inner);
        for (size_t k = 0; k < corners.size(); ++k) {
          geometry.circles.push_back(
              StaticCircle{Circle{corners[k].x_m, corners[k].y_m, spec.leg_radius_m},
                           spec.id + static_cast<int64_t>(k), spec.kind, index});
        }
        break;
      }
      case StaticShape::kBox:
      case StaticShape::kPolygon:
      case StaticShape::kPolyline: {
        const std::vector<PlanarPoint> vertices =
            spec.shape == StaticShape::kBox ? BoxCorners(spec) : spec.vertices;
        const bool closed = spec.shape != StaticShape::kPolyline;
        const size_t n = vertices.size();
        const size_t sides = closed ? n : n - 1;
        StaticSegment prototype;
        prototype.id = spec.id;
        prototype.kind = spec.kind;
        prototype.spec = index;
        for (size_t k = 0; k < sides; ++k) {
          AddSide(vertices[k], vertices[(k + 1) % n], static_cast<int>(k), spec.openings,
                  prototype, &geometry.segments);
        }
        break;
      }
    }
  }
  return geometry;
}

}  // namespace slammtt
