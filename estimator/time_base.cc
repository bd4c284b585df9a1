#include "estimator/time_base.h"

#include "common/utime.h"

namespace slammtt {

TimeVerdict StreamClock::Judge(int64_t utime, const TimeJumpLimits& limits) {
  if (!newest_) {
    newest_ = utime;
    run_length_ = 0;
    return TimeVerdict::kAccept;
  }
  const double ahead_s = SecondsBetween(utime, *newest_);
  if (ahead_s > 0.0 && ahead_s <= limits.forward_s) {
    newest_ = utime;
    run_length_ = 0;
    return TimeVerdict::kAccept;
  }
  if (ahead_s <= 0.0 && -ahead_s <= limits.back_s) {
    run_length_ = 0;
    return TimeVerdict::kLate;
  }
  // A jump: does it go on from the previous jumped message?
  const double after_run_s = SecondsBetween(utime, run_last_utime_);
  const bool continues_run =
      run_length_ > 0 && after_run_s > 0.0 && after_run_s <= limits.forward_s;
  run_length_ = continues_run ? run_length_ + 1 : 1;
  run_last_utime_ = utime;
  if (run_length_ < limits.confirm_messages) return TimeVerdict::kJumpHeld;
  newest_ = utime;
  run_length_ = 0;
  return ahead_s > 0.0 ? TimeVerdict::kNewTimeBaseAhead : TimeVerdict::kNewTimeBaseBack;
}

void StreamClock::Reset() {
  newest_.reset();
  run_length_ = 0;
}

const char* TimeVerdictName(TimeVerdict verdict) {
  switch (verdict) {
    case TimeVerdict::kAccept:
      return "accept";
    case TimeVerdict::kLate:
      return "late";
    case TimeVerdict::kJumpHeld:
      return "jump held";
    case TimeVerdict::kNewTimeBaseBack:
      return "new time base back";
    case TimeVerdict::kNewTimeBaseAhead:
      return "new time base ahead";
  }
  return "?";
}

}  // namespace slammtt
