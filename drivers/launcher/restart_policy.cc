#include "drivers/launcher/restart_policy.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

RestartPolicy::RestartPolicy(const LaunchPlan& plan, RestartMode mode)
    : initial_s_(plan.restart_initial_s),
      max_s_(plan.restart_max_s),
      reset_after_s_(plan.restart_reset_after_s),
      max_restarts_(plan.max_restarts),
      mode_(mode) {}

RestartPolicy::Decision RestartPolicy::OnExit(double started_s, double ended_s, bool clean) {
  Decision decision;
  if (mode_ == RestartMode::kNever || (clean && mode_ == RestartMode::kOnFailure)) {
    decision.gave_up = !clean;
    return decision;
  }
  if (ended_s - started_s >= reset_after_s_) restarts_in_a_row_ = 0;
  if (restarts_in_a_row_ >= max_restarts_) {
    decision.gave_up = true;
    return decision;
  }
  decision.restart = true;
  decision.delay_s = std::min(max_s_, initial_s_ * std::pow(2.0, restarts_in_a_row_));
  ++restarts_in_a_row_;
  return decision;
}

}  // namespace slammtt
