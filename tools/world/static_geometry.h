// The static world as the ray caster sees it: every static object of a scenario expanded into
// circles (posts, pillars, chair and table legs) and straight segments (the sides of walls,
// desks, cabinets and boxes, with door openings cut out), each remembering the object it belongs
// to. Built once per simulation; nothing here changes with time.
#pragma once

#include <cstdint>
#include <vector>

#include "tools/world/ray_caster.h"
#include "tools/world/scenario.h"

namespace slammtt {

struct StaticCircle {
  Circle circle;
  int64_t id = 0;  // object id (a chair's legs: id .. id + 3)
  ObjectKind kind = ObjectKind::kPost;
  int spec = 0;    // index into Scenario::statics
};

struct StaticSegment {
  Segment segment;
  int64_t id = 0;  // id of the object the side belongs to (every side of a room shares it)
  ObjectKind kind = ObjectKind::kWall;
  int spec = 0;    // index into Scenario::statics
};

struct StaticGeometry {
  std::vector<StaticCircle> circles;    // in scenario order
  std::vector<StaticSegment> segments;  // in scenario order, sides in vertex order
};

// Expands the statics (free of FindScenarioProblems() problems):
//   kCircle: one circle; kLegs: four circles of leg_radius_m centred leg_radius_m inside the
//   corners of the box, ids id .. id + 3 counter-clockwise from the rear right corner;
//   kBox: four sides (a closed polygon); kPolygon and kPolyline: one segment per side, a side
//   with openings split into the pieces between them (a piece shorter than 1 mm is dropped).
StaticGeometry BuildStaticGeometry(const std::vector<StaticObjectSpec>& statics);

// The corners of a kBox or kLegs spec, counter-clockwise from (-size_x/2, -size_y/2) in the
// box's own frame.
std::vector<PlanarPoint> BoxCorners(const StaticObjectSpec& spec);

}  // namespace slammtt
