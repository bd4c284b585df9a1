#include "drivers/command_auth/command_signature.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace slammtt {
namespace {

constexpr int64_t kNow = 1700000000000000;  // the robot's wall clock [us]

CommandKey TestKey(uint8_t first = 0x42) {
  CommandKey key{};
  for (size_t k = 0; k < key.size(); ++k) key[k] = static_cast<uint8_t>(first + k);
  return key;
}

slammtt_msgs::velocity_command_t Command(int64_t utime, double linear, double angular) {
  slammtt_msgs::velocity_command_t c{};
  c.utime = utime;
  c.linear_mps = linear;
  c.angular_radps = angular;
  return c;
}

std::string Hex(const int8_t* bytes, size_t n) {
  static const char kDigits[] = "0123456789abcdef";
  std::string text;
  for (size_t k = 0; k < n; ++k) {
    const auto b = static_cast<uint8_t>(bytes[k]);
    text += kDigits[b >> 4];
    text += kDigits[b & 15];
  }
  return text;
}

// The tag of one command, computed independently of this code with Python's hmac module over
// b"slammtt velocity_command_t v1\0" + b"VELOCITY_COMMAND\0" + the LCM encoding (fingerprint
// 8 bytes, then utime, linear_mps, angular_radps, sender_id, counter big-endian and 32 zero tag
// bytes), key bytes 0x42..0x61. A base station written in another language must give the same.
TEST(CommandSignatureTest, TagMatchesAnIndependentHmacSha256) {
  slammtt_msgs::velocity_command_t c = Command(kNow, 0.25, -0.5);
  c.sender_id = 0x0123456789abcdefLL;
  c.counter = 7;
  const CommandTag tag = VelocityCommandTag(TestKey(), "VELOCITY_COMMAND", c);
  EXPECT_EQ(Hex(reinterpret_cast<const int8_t*>(tag.data()), tag.size()),
            "5389209bded204c05433dd7519d6d05e7bca5c4bdb33de6d0514efbeee8cea69");
}

TEST(CommandSignatureTest, SignerCountsAndTheTagCoversEveryFieldTheChannelAndTheKey) {
  VelocityCommandSigner signer(TestKey(), "VELOCITY_COMMAND", 99);
  slammtt_msgs::velocity_command_t a = Command(kNow, 0.3, 0.1);
  signer.Sign(&a);
  EXPECT_EQ(a.sender_id, 99);
  EXPECT_EQ(a.counter, 1);
  slammtt_msgs::velocity_command_t b = Command(kNow, 0.3, 0.1);
  signer.Sign(&b);
  EXPECT_EQ(b.counter, 2);
  EXPECT_NE(std::memcmp(a.tag, b.tag, sizeof a.tag), 0);

  const CommandTag right = VelocityCommandTag(TestKey(), "VELOCITY_COMMAND", a);
  EXPECT_EQ(std::memcmp(right.data(), a.tag, right.size()), 0);
  EXPECT_NE(VelocityCommandTag(TestKey(), "VELOCITY_COMMAND_B", a), right);
  EXPECT_NE(VelocityCommandTag(TestKey(0x43), "VELOCITY_COMMAND", a), right);
  for (int field = 0; field < 5; ++field) {
    slammtt_msgs::velocity_command_t changed = a;
    if (field == 0) changed.utime += 1;
    if (field == 1) changed.linear_mps = 0.30000000000000004;
    if (field == 2) changed.angular_radps = -0.1;
    if (field == 3) changed.sender_id += 1;
    if (field == 4) changed.counter += 1;
    EXPECT_NE(VelocityCommandTag(TestKey(), "VELOCITY_COMMAND", changed), right) << field;
  }
  EXPECT_NE(NewSenderId(), NewSenderId());
}

TEST(CommandSignatureTest, VerifierAcceptsSignedCommandsOnceAndInOrder) {
  VelocityCommandSigner signer(TestKey(), "VELOCITY_COMMAND", 5);
  VelocityCommandVerifier verifier(TestKey(), "VELOCITY_COMMAND");
  slammtt_msgs::velocity_command_t first = Command(kNow, 0.2, 0.0);
  signer.Sign(&first);
  slammtt_msgs::velocity_command_t second = Command(kNow + 100000, 0.3, 0.0);
  signer.Sign(&second);
  EXPECT_EQ(verifier.Check(first, kNow + 1000), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Check(first, kNow + 2000), CommandVerdict::kReplayed);
  EXPECT_EQ(verifier.Check(second, kNow + 101000), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Check(second, kNow + 102000), CommandVerdict::kReplayed);
  EXPECT_EQ(verifier.Check(first, kNow + 103000), CommandVerdict::kReplayed);  // older counter

  // Another sender has its own counter.
  VelocityCommandSigner other(TestKey(), "VELOCITY_COMMAND", 6);
  slammtt_msgs::velocity_command_t theirs = Command(kNow + 110000, 0.0, 0.5);
  other.Sign(&theirs);
  EXPECT_EQ(verifier.Check(theirs, kNow + 111000), CommandVerdict::kAccepted);
}

TEST(CommandSignatureTest, VerifierRefusesUnsignedForgedWrongChannelAndStaleCommands) {
  VelocityCommandVerifier verifier(TestKey(), "VELOCITY_COMMAND");
  EXPECT_EQ(verifier.Check(Command(kNow, 0.4, 0.0), kNow), CommandVerdict::kUnauthenticated);

  VelocityCommandSigner signer(TestKey(), "VELOCITY_COMMAND", 1);
  slammtt_msgs::velocity_command_t forged = Command(kNow, 0.1, 0.0);
  signer.Sign(&forged);
  forged.linear_mps = 2.0;  // changed after signing
  EXPECT_EQ(verifier.Check(forged, kNow), CommandVerdict::kUnauthenticated);

  VelocityCommandSigner elsewhere(TestKey(), "VELOCITY_COMMAND_B", 2);
  slammtt_msgs::velocity_command_t wrong_channel = Command(kNow, 0.1, 0.0);
  elsewhere.Sign(&wrong_channel);
  EXPECT_EQ(verifier.Check(wrong_channel, kNow), CommandVerdict::kUnauthenticated);

  VelocityCommandSigner stranger(TestKey(0x07), "VELOCITY_COMMAND", 3);
  slammtt_msgs::velocity_command_t wrong_key = Command(kNow, 0.1, 0.0);
  stranger.Sign(&wrong_key);
  EXPECT_EQ(verifier.Check(wrong_key, kNow), CommandVerdict::kUnauthenticated);

  for (const int64_t offset_us :
       {int64_t{-1000001}, int64_t{1000001}, int64_t{-3600000000}, INT64_MAX - kNow}) {
    slammtt_msgs::velocity_command_t old = Command(kNow + offset_us, 0.1, 0.0);
    signer.Sign(&old);
    EXPECT_EQ(verifier.Check(old, kNow), CommandVerdict::kStale) << offset_us;
  }
  // The window's edges are inside.
  for (const int64_t offset_us : {int64_t{-1000000}, int64_t{999999}}) {
    slammtt_msgs::velocity_command_t edge = Command(kNow + offset_us, 0.1, 0.0);
    signer.Sign(&edge);
    EXPECT_EQ(verifier.Check(edge, kNow), CommandVerdict::kAccepted) << offset_us;
  }
}

TEST(CommandSignatureTest, VerifierForgetsStaleSendersFirstAndRefusesNewOnesWhenFull) {
  CommandVerifierOptions options;
  options.max_senders = 2;
  VelocityCommandVerifier verifier(TestKey(), "VELOCITY_COMMAND", options);
  const auto signed_by = [](int64_t sender, int64_t utime) {
    VelocityCommandSigner s(TestKey(), "VELOCITY_COMMAND", sender);
    slammtt_msgs::velocity_command_t c = Command(utime, 0.1, 0.0);
    s.Sign(&c);
    return c;
  };
  EXPECT_EQ(verifier.Check(signed_by(1, kNow), kNow), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Check(signed_by(2, kNow), kNow), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Check(signed_by(3, kNow), kNow), CommandVerdict::kReplayed);  // full
  // 1.5 s later senders 1 and 2 are stale: forgotten, room for new ones.
  const int64_t later = kNow + 1500000;
  EXPECT_EQ(verifier.Check(signed_by(3, later), later), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Check(signed_by(4, later), later), CommandVerdict::kAccepted);
  EXPECT_THROW(VelocityCommandVerifier(TestKey(), "X", CommandVerifierOptions{0.0, 64}),
               std::invalid_argument);
  EXPECT_THROW(VelocityCommandVerifier(TestKey(), "X", CommandVerifierOptions{1.0, 0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
