#include "tools/world/scattered_landmarks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "tools/world/portable_random.h"

namespace slammtt {
namespace {

// DeriveSeed's stream of the scattered landmarks (world_simulator.cc numbers its own 1-7).
constexpr uint64_t kScatteredLandmarkStream = 8;
constexpr int kDrawsPerLandmark = 1000;

struct PathPiece {
  PlanarPoint from;
  PlanarPoint to;
  double length_m = 0.0;
};

std::vector<PathPiece> Pieces(const std::vector<PlanarPoint>& path, bool closed) {
  std::vector<PathPiece> pieces;
  const size_t n = path.size();
  const size_t count = n < 2 ? 0 : (closed && n > 2 ? n : n - 1);
  for (size_t i = 0; i < count; ++i) {
    const PlanarPoint& a = path[i];
    const PlanarPoint& b = path[(i + 1) % n];
    const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    if (length > 0.0) pieces.push_back(PathPiece{a, b, length});
  }
  return pieces;
}

double DistanceToPiece(const PlanarPoint& p, const PathPiece& piece) {
  const double dx = piece.to.x_m - piece.from.x_m;
  const double dy = piece.to.y_m - piece.from.y_m;
  double t = ((p.x_m - piece.from.x_m) * dx + (p.y_m - piece.from.y_m) * dy) /
             (piece.length_m * piece.length_m);
  t = std::min(1.0, std::max(0.0, t));
  return std::hypot(p.x_m - (piece.from.x_m + t * dx), p.y_m - (piece.from.y_m + t * dy));
}

// Landmarks placed so far in cells of min_spacing_m, so that a draw looks at nine cells only.
class SpacingGrid {
 public:
  explicit SpacingGrid(double spacing_m) : spacing_m_(spacing_m) {}
  bool Free(const PlanarPoint& p) const {
    if (spacing_m_ <= 0.0) return true;
    const auto [cx, cy] = Cell(p);
    for (int64_t x = cx - 1; x <= cx + 1; ++x) {
      for (int64_t y = cy - 1; y <= cy + 1; ++y) {
        const auto it = cells_.find({x, y});
        if (it == cells_.end()) continue;
        for (const PlanarPoint& q : it->second) {
          if (std::hypot(p.x_m - q.x_m, p.y_m - q.y_m) < spacing_m_) return false;
        }
      }
    }
    return true;
  }
  void Add(const PlanarPoint& p) {
    if (spacing_m_ > 0.0) cells_[Cell(p)].push_back(p);
  }

 private:
  std::pair<int64_t, int64_t> Cell(const PlanarPoint& p) const {
    return {static_cast<int64_t>(std::floor(p.x_m / spacing_m_)),
            static_cast<int64_t>(std::floor(p.y_m / spacing_m_))};
  }
  double spacing_m_;
  std::map<std::pair<int64_t, int64_t>, std::vector<PlanarPoint>> cells_;
};

// One draw: a point of the path by arc length, moved across it to a random side.
PlanarPoint Draw(const ScatteredLandmarksSpec& spec, const std::vector<PathPiece>& pieces,
                 double total_m, std::mt19937_64& rng) {
  double along = UniformBetween(rng, 0.0, total_m);
  size_t k = 0;
  while (k + 1 < pieces.size() && along > pieces[k].length_m) along -= pieces[k++].length_m;
  const PathPiece& piece = pieces[k];
  const double ux = (piece.to.x_m - piece.from.x_m) / piece.length_m;
  const double uy = (piece.to.y_m - piece.from.y_m) / piece.length_m;
  const double side = UniformUnit(rng) < 0.5 ? -1.0 : 1.0;
  const double offset = side * UniformBetween(rng, spec.min_offset_m, spec.max_offset_m);
  return PlanarPoint{piece.from.x_m + along * ux - offset * uy,
                     piece.from.y_m + along * uy + offset * ux};
}

}  // namespace

std::vector<StaticObjectSpec> ScatterLandmarks(const ScatteredLandmarksSpec& spec,
                                               const std::vector<PlanarPoint>& path, bool closed,
                                               std::mt19937_64& rng) {
  std::vector<StaticObjectSpec> landmarks;
  const std::vector<PathPiece> pieces = Pieces(path, closed);
  if (spec.count <= 0 || pieces.empty()) return landmarks;
  double total_m = 0.0;
  for (const PathPiece& piece : pieces) total_m += piece.length_m;
  SpacingGrid placed(spec.min_spacing_m);
  for (int i = 0; i < spec.count; ++i) {
    for (int draw = 0; draw < kDrawsPerLandmark; ++draw) {
      const PlanarPoint p = Draw(spec, pieces, total_m, rng);
      bool clear_of_path = true;
      for (const PathPiece& piece : pieces) {
        if (DistanceToPiece(p, piece) < spec.min_offset_m) {
          clear_of_path = false;
          break;
        }
      }
      if (!clear_of_path || !placed.Free(p)) continue;
      placed.Add(p);
      StaticObjectSpec landmark;
      landmark.id = spec.first_id + static_cast<int64_t>(landmarks.size());
      landmark.x_m = p.x_m;
      landmark.y_m = p.y_m;
      landmark.radius_m = spec.radius_m;
      landmark.kind = ObjectKind::kPost;
      landmark.shape = StaticShape::kCircle;
      landmarks.push_back(landmark);
      break;
    }
  }
  return landmarks;
}

Scenario WithScatteredLandmarks(const Scenario& scenario, uint64_t seed) {
  Scenario out = scenario;
  const ScatteredLandmarksSpec& spec = scenario.scattered_landmarks;
  if (spec.count <= 0) return out;
  ScatteredLandmarksSpec numbered = spec;
  if (numbered.first_id == 0) {
    numbered.first_id = 1;
    for (const StaticObjectSpec& s : scenario.statics) {
      numbered.first_id = std::max(numbered.first_id, s.id + StaticIdCount(s));
    }
  }
  std::mt19937_64 rng(DeriveSeed(seed, kScatteredLandmarkStream));
  const std::vector<StaticObjectSpec> landmarks =
      ScatterLandmarks(numbered, scenario.robot.waypoints, scenario.robot.loop, rng);
  if (static_cast<int>(landmarks.size()) < spec.count) {
    throw std::invalid_argument(
        "scattered_landmarks: room for " + std::to_string(landmarks.size()) + " of " +
        std::to_string(spec.count) + " landmarks at min_spacing_m " +
        std::to_string(spec.min_spacing_m) + " (lower count or min_spacing_m)");
  }
  out.statics.insert(out.statics.end(), landmarks.begin(), landmarks.end());
  out.scattered_landmarks.count = 0;
  return out;
}

}  // namespace slammtt
