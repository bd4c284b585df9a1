// SmootherScanInput (smoother_input.h) <-> smoother_input_t (lcmtypes/smoother_input_t.lcm):
// the estimator's stage writes it, slammtt-smoother reads it. Plain field copies both ways;
// the smoother library checks every number it is given (docs/smoother.md).
#pragma once

#include "estimator/smoother_input.h"
#include "slammtt_msgs/smoother_input_t.hpp"

namespace slammtt {

slammtt_msgs::smoother_input_t SmootherInputMessage(const SmootherScanInput& input);

SmootherScanInput SmootherScanInputFromMessage(const slammtt_msgs::smoother_input_t& message);

}  // namespace slammtt
