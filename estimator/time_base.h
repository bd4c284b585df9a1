// The time base of one input stream (FEATURES or ODOMETRY): which utimes continue the stream,
// which are late, and when a jump is a new time base rather than one corrupted utime.
//
// Against the newest accepted utime of the stream, a message's utime is
//  - accepted when it is newer by at most `forward_s`, or when it is the stream's first;
//  - late (kLate) when it is not newer, by at most `back_s`: an out-of-order message, dropped;
//  - a jump (kJumpHeld) when it is older by more than `back_s` or newer by more than
//    `forward_s`. One jump is never believed: a single corrupted utime (utime -1, a far-future
//    stamp) is dropped and counted, and the stream goes on from its old base.
// A new time base needs consistent evidence: `confirm_messages` jumped messages in a row, each
// newer than the one before by at most `forward_s` (a stream going on in its new time). The last
// of them is then kNewTimeBaseBack (the stream went back: a log played again, a restarted
// simulator, a clock stepped back; the caller starts the estimation over) or kNewTimeBaseAhead
// (it went ahead: a clock stepped forward, a paused process; the caller treats it as a time gap).
// A message that continues the old base (accepted or late) ends the run of jumped messages.
// With confirm_messages = 1 every jump is a new time base at once.
//
// Utime differences are taken in double (common/utime.h): utimes 2^63 us apart do not overflow.
#pragma once

#include <cstdint>
#include <optional>

namespace slammtt {

struct TimeJumpLimits {
  double back_s = 2.0;       // older than the newest by more: a jump (> 0)
  double forward_s = 2.0;    // newer than the newest by more: a jump (> 0)
  int confirm_messages = 3;  // jumped messages in a row that make a new time base (>= 1)
};

enum class TimeVerdict {
  kAccept,             // continues the stream
  kLate,               // not newer than the newest, within back_s: drop
  kJumpHeld,           // a jump not (yet) confirmed: drop
  kNewTimeBaseBack,    // the confirming message of a new time base in the past
  kNewTimeBaseAhead,   // the confirming message of a new time base ahead
};

class StreamClock {
 public:
  // The verdict on a message at `utime`. Accepted messages (kAccept, kNewTimeBase*) become the
  // stream's newest; the others change only the run of jumped messages.
  TimeVerdict Judge(int64_t utime, const TimeJumpLimits& limits);

  // Forgets the stream (the estimation started over): the next message is a first one.
  void Reset();

  const std::optional<int64_t>& newest() const { return newest_; }
  // Jumped messages in the current run (0 when the last message continued the stream).
  int jumped_in_a_row() const { return run_length_; }

 private:
  std::optional<int64_t> newest_;
  int64_t run_last_utime_ = 0;
  int run_length_ = 0;
};

const char* TimeVerdictName(TimeVerdict verdict);

}  // namespace slammtt
