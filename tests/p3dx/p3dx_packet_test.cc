// Framing, checksum, command encoding and the streaming decoder, against byte vectors computed
// by hand from ../shared/design/protocols/p3dx.md (independent of the code under test).
#include <gtest/gtest.h>

#include <vector>

#include "drivers/p3dx/p3dx_commands.h"
#include "drivers/p3dx/p3dx_packet.h"

namespace slammtt {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(P3dxPacketTest, ChecksumOfEvenAndOddPayloads) {
  const Bytes enable = {0x04, 0x3B, 0x01, 0x00};  // 0x043B + 0x0100 = 0x053B
  EXPECT_EQ(P3dxChecksum(enable.data(), enable.size()), 0x053B);
  const Bytes odd = {0x01, 0x02, 0x03};           // 0x0102, then 0x03 XORed into the low byte
  EXPECT_EQ(P3dxChecksum(odd.data(), odd.size()), 0x0101);
  const Bytes overflow = {0xFF, 0xFF, 0x00, 0x02};  // 0xFFFF + 0x0002 truncated = 0x0001
  EXPECT_EQ(P3dxChecksum(overflow.data(), overflow.size()), 0x0001);
}

TEST(P3dxPacketTest, CommandsMatchTheWorkedExamples) {
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kEnable, 1),
            (Bytes{0xFA, 0xFB, 0x06, 0x04, 0x3B, 0x01, 0x00, 0x05, 0x3B}));
  EXPECT_EQ(EncodeP3dxCommand(p3dx_command::kSync0), (Bytes{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  EXPECT_EQ(EncodeP3dxVel2(-5, 10),
            (Bytes{0xFA, 0xFB, 0x06, 0x20, 0x1B, 0xF6, 0x04, 0x16, 0x1F}));
}

TEST(P3dxPacketTest, MoreCommandsComputedByHand) {
  // SYNC1: payload 01, odd: 0 ^ 0x01 = 0x0001.
  EXPECT_EQ(EncodeP3dxCommand(p3dx_command::kSync1), (Bytes{0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01}));
  // SYNC2: payload 02.
  EXPECT_EQ(EncodeP3dxCommand(p3dx_command::kSync2), (Bytes{0xFA, 0xFB, 0x03, 0x02, 0x00, 0x02}));
  // ESTOP (55 = 0x37).
  EXPECT_EQ(EncodeP3dxCommand(p3dx_command::kEstop), (Bytes{0xFA, 0xFB, 0x03, 0x37, 0x00, 0x37}));
  // VEL -300 mm/s: 0x0B 0x1B, |-300| = 0x012C -> 2C 01; 0x0B1B + 0x2C01 = 0x371C.
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kVel, -300),
            (Bytes{0xFA, 0xFB, 0x06, 0x0B, 0x1B, 0x2C, 0x01, 0x37, 0x1C}));
  // RVEL +15 deg/s: 0x153B + 0x0F00 = 0x243B.
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kRvel, 15),
            (Bytes{0xFA, 0xFB, 0x06, 0x15, 0x3B, 0x0F, 0x00, 0x24, 0x3B}));
  // VEL2 left +5, right -10: pattern 0x05F6 is positive: 0x203B + 0xF605 = 0x11640 -> 0x1640.
  EXPECT_EQ(EncodeP3dxVel2(5, -10), (Bytes{0xFA, 0xFB, 0x06, 0x20, 0x3B, 0xF6, 0x05, 0x16, 0x40}));
  // HOSTBAUD 2 (38400): 0x323B + 0x0200 = 0x343B.
  ASSERT_EQ(P3dxHostBaudIndex(38400), 2);
  EXPECT_FALSE(P3dxHostBaudIndex(4800).has_value());
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kHostBaud, 2),
            (Bytes{0xFA, 0xFB, 0x06, 0x32, 0x3B, 0x02, 0x00, 0x34, 0x3B}));
  // A string argument: command 15, "AB": 0x0F2B + 0x0241 = 0x116C, odd: 0x116C ^ 0x42 = 0x112E.
  EXPECT_EQ(EncodeP3dxStringCommand(15, "AB"),
            (Bytes{0xFA, 0xFB, 0x07, 0x0F, 0x2B, 0x02, 0x41, 0x42, 0x11, 0x2E}));
}

TEST(P3dxPacketTest, IntegerArgumentsAreClamped) {
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kVel, 100000),
            EncodeP3dxIntCommand(p3dx_command::kVel, 32767));
  EXPECT_EQ(EncodeP3dxIntCommand(p3dx_command::kVel, -100000),
            EncodeP3dxIntCommand(p3dx_command::kVel, -32767));
  EXPECT_EQ(EncodeP3dxVel2(-500, 500), EncodeP3dxVel2(-127, 127));
}

TEST(P3dxPacketTest, Vel2RoundTripsThroughTheDeviceParser) {
  for (int left = -127; left <= 127; left += 7) {
    for (int right = -127; right <= 127; right += 11) {
      const Bytes packet = EncodeP3dxVel2(left, right);
      P3dxPacketDecoder decoder;
      decoder.Feed(packet.data(), packet.size());
      const auto payload = decoder.Next();
      ASSERT_TRUE(payload.has_value());
      const auto command = ParseP3dxClientCommand(*payload);
      ASSERT_TRUE(command.has_value());
      EXPECT_EQ(command->number, p3dx_command::kVel2);
      int l = 0;
      int r = 0;
      SplitP3dxVel2(command->value, &l, &r);
      EXPECT_EQ(l, left);
      EXPECT_EQ(r, right);
    }
  }
}

TEST(P3dxPacketTest, ClientCommandParserRejectsMalformedArguments) {
  EXPECT_FALSE(ParseP3dxClientCommand({}).has_value());
  EXPECT_FALSE(ParseP3dxClientCommand({0x0B, 0x3B, 0x01}).has_value());   // 1 of 2 int bytes
  EXPECT_FALSE(ParseP3dxClientCommand({0x0B, 0x77, 0x01, 0x00}).has_value());  // unknown type
  EXPECT_FALSE(ParseP3dxClientCommand({0x0F, 0x2B, 0x05, 0x41}).has_value());  // string too short
  const auto bare = ParseP3dxClientCommand({0x02});
  ASSERT_TRUE(bare.has_value());
  EXPECT_EQ(bare->argument, P3dxClientCommand::Argument::kNone);
  const auto negative = ParseP3dxClientCommand({0x0B, 0x1B, 0x2C, 0x01});
  ASSERT_TRUE(negative.has_value());
  EXPECT_EQ(negative->value, -300);
}

TEST(P3dxPacketTest, DecoderSplitsAStreamFedByteByByte) {
  Bytes stream = EncodeP3dxCommand(p3dx_command::kSync0);
  const Bytes enable = EncodeP3dxIntCommand(p3dx_command::kEnable, 1);
  stream.insert(stream.end(), enable.begin(), enable.end());
  P3dxPacketDecoder decoder;
  std::vector<Bytes> payloads;
  for (uint8_t byte : stream) {
    decoder.Feed(&byte, 1);
    while (auto p = decoder.Next()) payloads.push_back(*p);
  }
  ASSERT_EQ(payloads.size(), 2u);
  EXPECT_EQ(payloads[0], (Bytes{0x00}));
  EXPECT_EQ(payloads[1], (Bytes{0x04, 0x3B, 0x01, 0x00}));
  EXPECT_EQ(decoder.counters().packets, 2);
  EXPECT_EQ(decoder.counters().bytes_skipped, 0);
  EXPECT_FALSE(decoder.HasPartial());
}

TEST(P3dxPacketTest, DecoderResyncsAfterGarbageAndBadChecksum) {
  Bytes stream = {0x00, 0x13, 0xFA, 0x77, 0xFB};  // garbage, including a lone header byte
  Bytes bad = EncodeP3dxIntCommand(p3dx_command::kEnable, 1);
  bad.back() ^= 0xFF;  // bad checksum
  stream.insert(stream.end(), bad.begin(), bad.end());
  const Bytes good = EncodeP3dxIntCommand(p3dx_command::kVel, 250);
  stream.insert(stream.end(), good.begin(), good.end());
  P3dxPacketDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  const auto payload = decoder.Next();
  ASSERT_TRUE(payload.has_value());
  EXPECT_EQ((*payload)[0], p3dx_command::kVel);
  EXPECT_FALSE(decoder.Next().has_value());
  EXPECT_EQ(decoder.counters().checksum_errors, 1);
  EXPECT_EQ(decoder.counters().packets, 1);
  EXPECT_EQ(decoder.counters().bytes_skipped, 5 + static_cast<int64_t>(bad.size()));
}

TEST(P3dxPacketTest, DecoderFindsAPacketHiddenInAFalseFrame) {
  // A false header announcing 40 bytes swallows a real packet; the checksum of the false frame
  // fails and the real packet inside is still decoded.
  Bytes stream = {0xFA, 0xFB, 40};
  const Bytes good = EncodeP3dxIntCommand(p3dx_command::kRvel, 10);
  stream.insert(stream.end(), good.begin(), good.end());
  stream.resize(3 + 40, 0x00);
  P3dxPacketDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  const auto payload = decoder.Next();
  ASSERT_TRUE(payload.has_value());
  EXPECT_EQ((*payload)[0], p3dx_command::kRvel);
  EXPECT_EQ(decoder.counters().checksum_errors, 1);
}

TEST(P3dxPacketTest, DecoderRejectsImpossibleByteCounts) {
  const Bytes stream = {0xFA, 0xFB, 0x02, 0xFA, 0xFB, 0xF0, 0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00};
  P3dxPacketDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  const auto payload = decoder.Next();
  ASSERT_TRUE(payload.has_value());
  EXPECT_EQ(*payload, (Bytes{0x00}));
  EXPECT_EQ(decoder.counters().bad_byte_counts, 2);
}

TEST(P3dxPacketTest, DiscardPartialCountsATruncatedPacketAndKeepsWhatFollows) {
  const Bytes good = EncodeP3dxCommand(p3dx_command::kSync0);
  Bytes stream = {0xFA, 0xFB, 0x20, 0x01, 0x02};  // a packet that never ends
  stream.insert(stream.end(), good.begin(), good.end());
  P3dxPacketDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  EXPECT_FALSE(decoder.Next().has_value());
  EXPECT_TRUE(decoder.HasPartial());
  decoder.DiscardPartial();
  EXPECT_FALSE(decoder.HasPartial());
  EXPECT_EQ(decoder.counters().truncated, 1);
  const auto payload = decoder.Next();
  ASSERT_TRUE(payload.has_value());
  EXPECT_EQ(*payload, (Bytes{0x00}));
}

TEST(P3dxPacketTest, FrameRejectsEmptyAndOversizedPayloads) {
  EXPECT_THROW(FrameP3dxPacket({}), std::invalid_argument);
  EXPECT_THROW(FrameP3dxPacket(Bytes(kP3dxMaxPayload + 1, 0)), std::invalid_argument);
  EXPECT_EQ(FrameP3dxPacket(Bytes(kP3dxMaxPayload, 0))[2], kP3dxMaxByteCount);
}

}  // namespace
}  // namespace slammtt
