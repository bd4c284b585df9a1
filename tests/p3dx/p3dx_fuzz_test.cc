// Fuzz-style tests of the receive path: random and mutated packets into the decoder and the SIP
// parser, and the whole driver against a robot whose line is damaged at random. Seeded, so a
// failure reproduces; SLAMMTT_LONG_TESTS=1 runs 20 times as many rounds.
//
// What "no odometry from a bad packet" can mean with a 16-bit checksum: a damage the checksum
// always detects (any one byte changed or one bit flipped in payload or checksum) never gives a
// packet; damage that shifts the frame (truncation, lost or added bytes, a changed byte count,
// random bytes) is caught with probability 1 - 2^-16 per false frame, and the test bounds the
// false accepts by that rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "drivers/p3dx/p3dx_driver.h"
#include "drivers/p3dx/p3dx_packet.h"
#include "drivers/p3dx/p3dx_sip.h"
#include "simulated_robot_link.h"

namespace slammtt {
namespace {

using Bytes = std::vector<uint8_t>;

int Rounds(int normal) {
  const char* long_tests = std::getenv("SLAMMTT_LONG_TESTS");
  return long_tests != nullptr && std::string(long_tests) == "1" ? 20 * normal : normal;
}

// A random but valid SIP payload, made unique by `serial`.
Bytes RandomSip(std::mt19937_64& random, uint32_t serial) {
  std::uniform_int_distribution<int> u16(0, 65535);
  std::uniform_int_distribution<int> u8(0, 255);
  P3dxStandardSip sip;
  sip.moving = (serial & 1) != 0;
  sip.x_pos = static_cast<uint16_t>(serial & 0x7FFF);
  sip.y_pos = static_cast<uint16_t>((serial >> 15) & 0x7FFF);
  sip.th_pos = static_cast<int16_t>(u16(random));
  sip.left_vel = static_cast<int16_t>(u16(random));
  sip.right_vel = static_cast<int16_t>(u16(random));
  sip.battery_decivolts = static_cast<uint8_t>(u8(random));
  sip.stall_and_bumpers = static_cast<uint16_t>(u16(random));
  sip.flags = static_cast<uint16_t>(u16(random));
  const int sonars = std::uniform_int_distribution<int>(0, 8)(random);
  for (int i = 0; i < sonars; ++i) {
    sip.sonars.push_back({static_cast<uint8_t>(i), static_cast<uint16_t>(u16(random))});
  }
  if (u8(random) < 128) sip.rot_vel_decideg_per_s = static_cast<int16_t>(u16(random));
  return EncodeP3dxStandardSip(sip);
}

Bytes Garbage(std::mt19937_64& random, int size, bool allow_header) {
  std::uniform_int_distribution<int> u8(0, 255);
  Bytes bytes;
  while (static_cast<int>(bytes.size()) < size) {
    const uint8_t b = static_cast<uint8_t>(u8(random));
    if (allow_header || b != kP3dxHeader0) bytes.push_back(b);
  }
  return bytes;
}

// Feeds `stream` in random chunks and returns every payload that came out.
std::vector<Bytes> DecodeInChunks(const Bytes& stream, std::mt19937_64& random,
                                  P3dxPacketDecoder* decoder) {
  std::vector<Bytes> out;
  std::uniform_int_distribution<size_t> chunk(1, 64);
  for (size_t i = 0; i < stream.size();) {
    const size_t n = std::min(chunk(random), stream.size() - i);
    decoder->Feed(stream.data() + i, n);
    i += n;
    while (auto payload = decoder->Next()) out.push_back(*payload);
  }
  return out;
}

TEST(P3dxFuzzTest, DamageTheChecksumAlwaysDetectsNeverGivesAPacket) {
  std::mt19937_64 random(20240601);
  int64_t mutated = 0;
  int64_t valid = 0;
  const int rounds = Rounds(24000);
  P3dxPacketDecoder decoder;
  for (int round = 0; round < rounds; ++round) {
    Bytes stream;
    std::vector<Bytes> expected;
    for (int segment = 0; segment < 40; ++segment) {
      const uint32_t serial = static_cast<uint32_t>(round * 64 + segment);
      const Bytes payload = RandomSip(random, serial);
      Bytes packet = FrameP3dxPacket(payload);
      switch (std::uniform_int_distribution<int>(0, 3)(random)) {
        case 0: {  // one byte of payload or checksum replaced by a different value
          const size_t at = std::uniform_int_distribution<size_t>(3, packet.size() - 1)(random);
          packet[at] = static_cast<uint8_t>(packet[at] + std::uniform_int_distribution<int>(1, 255)(random));
          ++mutated;
          break;
        }
        case 1: {  // one bit flipped
          const size_t at = std::uniform_int_distribution<size_t>(3, packet.size() - 1)(random);
          packet[at] ^= static_cast<uint8_t>(1u << std::uniform_int_distribution<int>(0, 7)(random));
          ++mutated;
          break;
        }
        default:
          expected.push_back(payload);
          ++valid;
          break;
      }
      stream.insert(stream.end(), packet.begin(), packet.end());
      if (std::uniform_int_distribution<int>(0, 3)(random) == 0) {
        const Bytes junk = Garbage(random, std::uniform_int_distribution<int>(1, 50)(random), false);
        stream.insert(stream.end(), junk.begin(), junk.end());
      }
    }
    std::vector<Bytes> decoded = DecodeInChunks(stream, random, &decoder);
    // A replaced byte can be a false header whose frame is still waiting for bytes: the link
    // going quiet releases the packets behind it.
    decoder.DiscardPartial();
    while (auto payload = decoder.Next()) decoded.push_back(*payload);
    ASSERT_EQ(decoded, expected) << "round " << round;
    for (const Bytes& payload : decoded) {
      ASSERT_EQ(ParseP3dxStandardSip(payload).status, P3dxSipStatus::kOk);
    }
  }
  EXPECT_EQ(decoder.counters().packets, valid);
  // A replaced byte inside the mutated frame can itself be a header, so a checksum error can be
  // counted more than once per mutated packet, never less.
  EXPECT_GE(decoder.counters().checksum_errors + decoder.counters().bad_byte_counts, mutated);
  RecordProperty("valid_packets", std::to_string(valid));
  RecordProperty("mutated_packets", std::to_string(mutated));
}

TEST(P3dxFuzzTest, FrameShiftingDamageIsCaughtAtTheChecksumRate) {
  std::mt19937_64 random(77);
  const int rounds = Rounds(15000);
  P3dxPacketDecoder decoder;
  std::set<Bytes> valid_payloads;
  int64_t false_accepts = 0;
  int64_t intact_content = 0;
  int64_t valid_sent = 0;
  int64_t valid_received = 0;
  for (int round = 0; round < rounds; ++round) {
    Bytes stream;
    std::set<Bytes> sent;      // packets sent intact
    std::set<Bytes> contents;  // every payload, damaged or not
    for (int segment = 0; segment < 40; ++segment) {
      const Bytes payload = RandomSip(random, static_cast<uint32_t>(round * 64 + segment));
      contents.insert(payload);
      Bytes packet = FrameP3dxPacket(payload);
      bool damaged = true;
      switch (std::uniform_int_distribution<int>(0, 6)(random)) {
        case 0:  // truncated anywhere
          packet.resize(std::uniform_int_distribution<size_t>(1, packet.size() - 1)(random));
          break;
        case 1: {  // bytes lost
          const size_t at = std::uniform_int_distribution<size_t>(0, packet.size() - 1)(random);
          packet.erase(packet.begin() + static_cast<std::ptrdiff_t>(at));
          break;
        }
        case 2: {  // a byte added inside the frame (before or after it leaves the frame intact)
          const size_t at = std::uniform_int_distribution<size_t>(1, packet.size() - 1)(random);
          packet.insert(packet.begin() + static_cast<std::ptrdiff_t>(at),
                        static_cast<uint8_t>(std::uniform_int_distribution<int>(0, 255)(random)));
          break;
        }
        case 3:  // the byte count changed
          packet[2] = static_cast<uint8_t>(packet[2] + std::uniform_int_distribution<int>(1, 255)(random));
          break;
        case 4: {  // random bytes, headers included
          const Bytes junk = Garbage(random, std::uniform_int_distribution<int>(1, 300)(random), true);
          stream.insert(stream.end(), junk.begin(), junk.end());
          damaged = false;
          break;
        }
        default:
          damaged = false;
          break;
      }
      if (!damaged) {
        sent.insert(payload);
        ++valid_sent;
      }
      stream.insert(stream.end(), packet.begin(), packet.end());
    }
    std::vector<Bytes> decoded = DecodeInChunks(stream, random, &decoder);
    decoder.DiscardPartial();  // the link goes quiet: complete packets behind a false frame come out
    while (auto payload = decoder.Next()) decoded.push_back(*payload);
    for (const Bytes& payload : decoded) {
      if (sent.count(payload) > 0) {
        ++valid_received;
      } else if (contents.count(payload) > 0) {
        // Damage only around the checksum (a checksum byte lost or split, the byte after it
        // equal to the lost one): the content is the robot's own, nothing false came out.
        ++intact_content;
      } else {
        ++false_accepts;
        // Even a false frame must be harmless to the parser.
        ParseP3dxStandardSip(payload);
      }
    }
  }
  const double candidates = static_cast<double>(decoder.counters().checksum_errors + false_accepts);
  const double expected_false = candidates / 65536.0;
  EXPECT_LE(false_accepts, 4.0 * expected_false + 4.0)
      << candidates << " false frames checked, " << false_accepts << " passed the checksum";
  // Valid packets next to damaged ones are found again by rescanning; only a frame that passed
  // the checksum while it was not the packet it claimed to be can have swallowed one (a lost
  // checksum byte replaced by the next packet's 0xFA takes that packet's header with it).
  EXPECT_GE(valid_received, valid_sent - 2 * (false_accepts + intact_content));
  RecordProperty("false_frames_checked", std::to_string(static_cast<int64_t>(candidates)));
  RecordProperty("false_accepts", std::to_string(false_accepts));
  RecordProperty("damaged_frames_with_intact_content", std::to_string(intact_content));
}

TEST(P3dxFuzzTest, SipParserIsBoundedOnAnyPayload) {
  std::mt19937_64 random(5);
  const int rounds = Rounds(1000000);
  for (int round = 0; round < rounds; ++round) {
    const int size = std::uniform_int_distribution<int>(1, static_cast<int>(kP3dxMaxPayload))(random);
    Bytes payload = Garbage(random, size, true);
    payload[0] = (round & 1) != 0 ? kP3dxSipMoving : kP3dxSipStopped;
    const P3dxSipParse parse = ParseP3dxStandardSip(payload);
    const bool long_enough = payload.size() >= 20 && payload.size() >= 20u + 3u * payload[19];
    ASSERT_EQ(parse.status == P3dxSipStatus::kOk, long_enough) << round;
    if (long_enough) {
      ASSERT_EQ(parse.sip.sonars.size(), payload[19]);
      ASSERT_LT(parse.sip.x_pos, 32768);
    }
    ParseP3dxRobotIdentity(payload);
  }
}

// The driver against a robot whose line is damaged at random (checksum-detectable damage and
// header-free garbage), in simulated time: every SIP that arrives intact gives exactly one
// ODOMETRY and no damaged one gives any.
TEST(P3dxFuzzTest, DriverOnADamagedLineNeverPublishesABadPose) {
  SimulatedClock clock;
  P3dxRobotModelOptions robot_options;
  robot_options.seed = 99;
  SimulatedRobot robot(robot_options, &clock);
  RecordingSink sink;
  P3dxDriverOptions options;
  P3dxDriver driver(options, [&](const std::string& e, int b) { return robot.Open(e, b); }, &clock,
                    &sink);
  std::mt19937_64 random(1234);
  const int64_t end = clock.now_us + static_cast<int64_t>(Rounds(6000)) * 1000000;  // simulated s
  int64_t next_command = clock.now_us;
  int64_t damaged = 0;
  int64_t sips_at_start = -1;
  size_t odometry_at_start = 0;
  int64_t last_damaged_sip = -1;
  while (clock.now_us < end) {
    const int64_t before = clock.now_us;
    driver.Poll(10);
    if (driver.state() == P3dxDriver::State::kRunning && sips_at_start < 0) {
      sips_at_start = robot.model().sips_sent();
      odometry_at_start = sink.odometry.size();
    }
    if (clock.now_us >= next_command) {
      slammtt_msgs::velocity_command_t command{};
      command.linear_mps = std::uniform_real_distribution<double>(-0.5, 0.5)(random);
      command.angular_radps = std::uniform_real_distribution<double>(-1.0, 1.0)(random);
      driver.HandleVelocityCommand(command);
      next_command += 100000;
    }
    // At most one damage per SIP, so that no packet is damaged twice and counted once.
    if (sips_at_start >= 0 && robot.model().sips_sent() > last_damaged_sip &&
        std::uniform_int_distribution<int>(0, 200)(random) == 0) {
      last_damaged_sip = robot.model().sips_sent();
      switch (std::uniform_int_distribution<int>(0, 2)(random)) {
        case 0:
          robot.model().CorruptNextChecksums(1);
          ++damaged;
          break;
        case 1:
          robot.model().SendShortSips(1);
          ++damaged;
          break;
        default:
          robot.model().InjectGarbage(std::uniform_int_distribution<int>(1, 80)(random), false);
          break;
      }
    }
    if (clock.now_us == before) clock.now_us += 1000;
    robot.Sync();
  }
  // Let the last command time out and the last damaged packets go by.
  const int64_t settle = clock.now_us + 2000000;
  while (clock.now_us < settle) {
    const int64_t before = clock.now_us;
    driver.Poll(10);
    if (clock.now_us == before) clock.now_us += 1000;
    robot.Sync();
  }
  ASSERT_GE(sips_at_start, 0);
  EXPECT_EQ(driver.state(), P3dxDriver::State::kRunning);
  EXPECT_EQ(driver.Status().reconnects, 0);
  const int64_t sips = robot.model().sips_sent() - sips_at_start;
  const int64_t published = static_cast<int64_t>(sink.odometry.size() - odometry_at_start);
  EXPECT_GT(damaged, 100);
  EXPECT_EQ(published, sips - damaged);
  EXPECT_EQ(driver.Status().checksum_errors + driver.Status().short_packets, damaged);
  ASSERT_FALSE(robot.model().moving());
  EXPECT_NEAR(sink.odometry.back().x_m, robot.model().x_mm() / 1000.0, 0.001);
  EXPECT_NEAR(sink.odometry.back().y_m, robot.model().y_mm() / 1000.0, 0.001);
}

}  // namespace
}  // namespace slammtt
