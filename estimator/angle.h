// Angle helpers of the estimator's models. Headings and bearings are wrapped to (-pi, pi], the
// project's frame convention (docs/DEVELOPING.md), by the project's one WrapAngle
// (common/angle.h: a second inline slammtt::WrapAngle here would break the one-definition rule
// in any program that links the estimator with the world or the metrics).
#pragma once

#include "common/angle.h"

namespace slammtt {

inline double DegreesToRadians(double degrees) { return degrees * M_PI / 180.0; }
inline double RadiansToDegrees(double radians) { return radians * 180.0 / M_PI; }

}  // namespace slammtt
