// When to restart a process of the stack that ended, and when to give up on it. Pure: the
// supervisor feeds it the times (monotonic seconds) at which the process started and ended.
//
// A process that ends is restarted after a backoff of restart_initial_s, doubling with every
// failure in a row up to restart_max_s; after max_restarts restarts in a row it is given up.
// A run that lasted restart_reset_after_s or more forgets the failures before it (a driver that
// ran for an hour and then lost its device starts again at the initial backoff).
#pragma once

#include "drivers/launcher/launch_plan.h"

namespace slammtt {

class RestartPolicy {
 public:
  RestartPolicy(const LaunchPlan& plan, RestartMode mode);

  struct Decision {
    bool restart = false;   // false: the process stays down (see gave_up)
    bool gave_up = false;   // it failed and will not be restarted: a failure of the stack
    double delay_s = 0.0;   // when restart: wait this long first
  };

  // The process that started at `started_s` ended at `ended_s`; `clean` is an exit status of 0.
  Decision OnExit(double started_s, double ended_s, bool clean);

  int restarts_in_a_row() const { return restarts_in_a_row_; }

 private:
  double initial_s_;
  double max_s_;
  double reset_after_s_;
  int max_restarts_;
  RestartMode mode_;
  int restarts_in_a_row_ = 0;
};

}  // namespace slammtt
