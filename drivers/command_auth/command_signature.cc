#include "drivers/command_auth/command_signature.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "common/utime.h"
#include "runtime/lcm_io.h"

namespace slammtt {
namespace {

constexpr char kDomain[] = "slammtt velocity_command_t v1";

// The bytes the tag covers (command_signature.h).
std::vector<uint8_t> SignedBytes(const std::string& channel,
                                 slammtt_msgs::velocity_command_t command) {
  std::fill(std::begin(command.tag), std::end(command.tag), int8_t{0});
  std::vector<uint8_t> bytes(kDomain, kDomain + sizeof kDomain);  // with its NUL
  bytes.insert(bytes.end(), channel.begin(), channel.end());
  bytes.push_back(0);
  const std::vector<uint8_t> encoded = Encode(command);
  bytes.insert(bytes.end(), encoded.begin(), encoded.end());
  return bytes;
}

}  // namespace

CommandTag VelocityCommandTag(const CommandKey& key, const std::string& channel,
                              const slammtt_msgs::velocity_command_t& command) {
  const std::vector<uint8_t> bytes = SignedBytes(channel, command);
  CommandTag tag{};
  unsigned int length = 0;
  if (HMAC(EVP_sha256(), key.data(), static_cast<int>(key.size()), bytes.data(), bytes.size(),
           tag.data(), &length) == nullptr ||
      length != tag.size()) {
    throw std::runtime_error("HMAC-SHA256 failed (OpenSSL)");
  }
  return tag;
}

VelocityCommandSigner::VelocityCommandSigner(const CommandKey& key, std::string channel,
                                             int64_t sender_id)
    : key_(key), channel_(std::move(channel)), sender_id_(sender_id) {}

void VelocityCommandSigner::Sign(slammtt_msgs::velocity_command_t* command) {
  command->sender_id = sender_id_;
  command->counter = ++counter_;
  const CommandTag tag = VelocityCommandTag(key_, channel_, *command);
  std::memcpy(command->tag, tag.data(), tag.size());
}

int64_t NewSenderId() {
  int64_t id = 0;
  if (RAND_bytes(reinterpret_cast<unsigned char*>(&id), sizeof id) != 1) {
    throw std::runtime_error("the random source failed (OpenSSL RAND_bytes)");
  }
  return id;
}

const char* CommandVerdictName(CommandVerdict verdict) {
  switch (verdict) {
    case CommandVerdict::kAccepted: return "accepted";
    case CommandVerdict::kUnauthenticated: return "unauthenticated (no tag or a wrong one)";
    case CommandVerdict::kStale: return "stale (utime outside the freshness window)";
    case CommandVerdict::kReplayed: return "replayed (counter not newer than the last one)";
  }
  return "unknown";
}

VelocityCommandVerifier::VelocityCommandVerifier(const CommandKey& key, std::string channel,
                                                 const CommandVerifierOptions& options)
    : key_(key), channel_(std::move(channel)), options_(options) {
  if (!(options_.max_age_s > 0.0 && options_.max_age_s <= 60.0)) {
    throw std::invalid_argument("command freshness window must be in (0, 60] s");
  }
  if (options_.max_senders < 1) throw std::invalid_argument("max_senders must be >= 1");
}

bool VelocityCommandVerifier::MakeRoom(int64_t now_utime) {
  if (static_cast<int>(senders_.size()) < options_.max_senders) return true;
  for (auto it = senders_.begin(); it != senders_.end();) {
    if (SecondsBetween(now_utime, it->second.utime) > options_.max_age_s) {
      it = senders_.erase(it);
    } else {
      ++it;
    }
  }
  return static_cast<int>(senders_.size()) < options_.max_senders;
}

CommandVerdict VelocityCommandVerifier::Check(const slammtt_msgs::velocity_command_t& command,
                                              int64_t now_utime) {
  const CommandTag expected = VelocityCommandTag(key_, channel_, command);
  if (CRYPTO_memcmp(expected.data(), command.tag, expected.size()) != 0) {
    return CommandVerdict::kUnauthenticated;
  }
  if (!(std::abs(SecondsBetween(command.utime, now_utime)) <= options_.max_age_s)) {
    return CommandVerdict::kStale;
  }
  auto it = senders_.find(command.sender_id);
  if (it == senders_.end()) {
    if (!MakeRoom(now_utime)) return CommandVerdict::kReplayed;
    it = senders_.emplace(command.sender_id, Sender{}).first;
  } else if (command.counter <= it->second.counter) {
    return CommandVerdict::kReplayed;
  }
  it->second.counter = command.counter;
  it->second.utime = command.utime;
  return CommandVerdict::kAccepted;
}

}  // namespace slammtt
