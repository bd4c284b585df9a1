// Authenticated VELOCITY_COMMAND: who may drive the robot (docs/robot.md, "Who can drive the
// robot"). Pure: no clock, no I/O, no random source; the caller passes the time and the sender
// id.
//
// Tag: HMAC-SHA256 (RFC 2104 with FIPS 180-4 SHA-256, computed by OpenSSL's HMAC()) with the
// shared CommandKey over
//   "slammtt velocity_command_t v1" NUL  channel NUL  LCM encoding of the command with tag zeroed
// so a tag binds every field (utime, speeds, sender_id, counter), the message type (the LCM
// encoding starts with the type's fingerprint) and the channel (a command signed for one robot's
// VELOCITY_COMMAND_A is no use on another robot's VELOCITY_COMMAND_B with the same key).
//
// A command is accepted (VelocityCommandVerifier::Check) when, in this order:
//  1. its tag is right (compared in constant time, CRYPTO_memcmp): else kUnauthenticated;
//  2. its utime is within max_age_s of the robot's clock, either way: else kStale; so a recorded
//     command cannot be played back later, and a base station's clock must agree with the
//     robot's within max_age_s (NTP or chrony);
//  3. its counter is greater than the last one accepted from its sender_id: else kReplayed; so a
//     command cannot be played back within the window either.
// The verifier remembers the last counter of at most max_senders senders. A sender whose last
// accepted command is older than max_age_s is forgotten first (every command it signed before is
// stale by then); when max_senders senders are all fresh, a new sender is refused (kReplayed)
// until one goes stale. After the verifier is created (the driver restarts) a command recorded
// in the last max_age_s could be accepted once: the window bounds that.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {

using CommandTag = std::array<uint8_t, 32>;

// The tag of `command` on `channel` (the tag field itself is ignored).
CommandTag VelocityCommandTag(const CommandKey& key, const std::string& channel,
                              const slammtt_msgs::velocity_command_t& command);

// Signs the commands of one sender: counter 1, 2, 3, ...
class VelocityCommandSigner {
 public:
  // `sender_id`: a random number per sender start (the caller draws it, e.g. NewSenderId()).
  VelocityCommandSigner(const CommandKey& key, std::string channel, int64_t sender_id);
  // Sets sender_id, the next counter and the tag of *command (its utime and speeds as given).
  void Sign(slammtt_msgs::velocity_command_t* command);
  int64_t last_counter() const { return counter_; }

 private:
  CommandKey key_;
  std::string channel_;
  int64_t sender_id_;
  int64_t counter_ = 0;
};

// A sender id from the operating system's random source (OpenSSL RAND_bytes); not pure, for the
// programs that sign. Throws std::runtime_error when the source fails.
int64_t NewSenderId();

enum class CommandVerdict { kAccepted, kUnauthenticated, kStale, kReplayed };
const char* CommandVerdictName(CommandVerdict verdict);

struct CommandVerifierOptions {
  double max_age_s = 1.0;  // freshness window, both ways, in (0, 60]
  int max_senders = 64;
};

class VelocityCommandVerifier {
 public:
  // Throws std::invalid_argument for options out of range.
  VelocityCommandVerifier(const CommandKey& key, std::string channel,
                          const CommandVerifierOptions& options = CommandVerifierOptions{});
  // Checks `command` received at `now_utime` (the robot's wall clock, us); remembers its counter
  // when it is accepted.
  CommandVerdict Check(const slammtt_msgs::velocity_command_t& command, int64_t now_utime);

 private:
  struct Sender {
    int64_t counter = 0;
    int64_t utime = 0;  // of the last accepted command
  };
  bool MakeRoom(int64_t now_utime);

  CommandKey key_;
  std::string channel_;
  CommandVerifierOptions options_;
  std::map<int64_t, Sender> senders_;
};

}  // namespace slammtt
