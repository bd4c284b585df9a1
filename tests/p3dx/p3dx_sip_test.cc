// SIP and name-packet parsing against a SIP built by hand, and the odometry integrator.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drivers/p3dx/p3dx_odometry.h"
#include "drivers/p3dx/p3dx_packet.h"
#include "drivers/p3dx/p3dx_sip.h"

namespace slammtt {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr double kPi = 3.14159265358979323846;

// A standard SIP written out by hand (ARCOS manual Table 4 field order, little-endian):
//   32          type: motors stopped
//   E8 03       XPOS 1000
//   F8 7F       YPOS 32760
//   00 04       THPOS 1024 (a quarter turn)
//   9C FF       L VEL -100
//   64 00       R VEL +100
//   7D          BATTERY 125 = 12.5 V
//   03 02       STALL AND BUMPERS 0x0203: left stall, left bumper 1, right bumper 1
//   00 00       CONTROL
//   01 00       FLAGS: motors enabled
//   2D          COMPASS 45 (90 degrees)
//   00          SONAR COUNT
// Byte count 20 + 2 = 0x16. Checksum, 16-bit big-endian words truncated to 16 bits:
//   32E8 + 03F8 = 36E0; + 7F00 = B5E0; + 049C = BA7C; + FF64 = B9E0; + 007D = BA5D;
//   + 0302 = BD5F; + 0000; + 0100 = BE5F; + 2D00 = EB5F (even length, no XOR) -> EB 5F.
const Bytes kHandSip = {0xFA, 0xFB, 0x16, 0x32, 0xE8, 0x03, 0xF8, 0x7F, 0x00, 0x04, 0x9C, 0xFF, 0x64,
                        0x00, 0x7D, 0x03, 0x02, 0x00, 0x00, 0x01, 0x00, 0x2D, 0x00, 0xEB, 0x5F};

Bytes DecodeOne(const Bytes& stream) {
  P3dxPacketDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  auto payload = decoder.Next();
  EXPECT_TRUE(payload.has_value());
  return payload.value_or(Bytes{});
}

TEST(P3dxSipTest, ParsesTheHandBuiltSip) {
  const Bytes payload = DecodeOne(kHandSip);
  ASSERT_EQ(payload.size(), 20u);
  const P3dxSipParse parse = ParseP3dxStandardSip(payload);
  ASSERT_EQ(parse.status, P3dxSipStatus::kOk);
  const P3dxStandardSip& sip = parse.sip;
  EXPECT_FALSE(sip.moving);
  EXPECT_EQ(sip.x_pos, 1000);
  EXPECT_EQ(sip.y_pos, 32760);
  EXPECT_EQ(sip.th_pos, 1024);
  EXPECT_EQ(sip.left_vel, -100);
  EXPECT_EQ(sip.right_vel, 100);
  EXPECT_DOUBLE_EQ(sip.battery_v(), 12.5);
  EXPECT_TRUE(sip.left_wheel_stalled());
  EXPECT_FALSE(sip.right_wheel_stalled());
  EXPECT_EQ(sip.bumpers(), 0x0101);
  EXPECT_TRUE(sip.motors_enabled());
  EXPECT_EQ(sip.compass, 0x2D);
  EXPECT_TRUE(sip.sonars.empty());
  EXPECT_FALSE(sip.io.has_value());
  EXPECT_FALSE(sip.rot_vel_decideg_per_s.has_value());
}

TEST(P3dxSipTest, EncodingTheSameFieldsGivesTheHandBuiltBytes) {
  P3dxStandardSip sip;
  sip.x_pos = 1000;
  sip.y_pos = 32760;
  sip.th_pos = 1024;
  sip.left_vel = -100;
  sip.right_vel = 100;
  sip.battery_decivolts = 125;
  sip.stall_and_bumpers = 0x0203;
  sip.flags = 1;
  sip.compass = 0x2D;
  EXPECT_EQ(FrameP3dxPacket(EncodeP3dxStandardSip(sip)), kHandSip);
}

TEST(P3dxSipTest, OptionalFieldsAndSonarsRoundTrip) {
  P3dxStandardSip sip;
  sip.moving = true;
  sip.x_pos = 32767;
  sip.th_pos = -5;
  sip.sonars = {{3, 1500}, {4, 250}};
  sip.battery_decivolts_x10 = 131;
  sip.rot_vel_decideg_per_s = -455;
  sip.fault_flags = 0x0F0F;
  const P3dxSipParse parse = ParseP3dxStandardSip(EncodeP3dxStandardSip(sip));
  ASSERT_EQ(parse.status, P3dxSipStatus::kOk);
  EXPECT_TRUE(parse.sip.moving);
  EXPECT_EQ(parse.sip.x_pos, 32767);
  EXPECT_EQ(parse.sip.th_pos, -5);
  ASSERT_EQ(parse.sip.sonars.size(), 2u);
  EXPECT_EQ(parse.sip.sonars[1].number, 4);
  EXPECT_EQ(parse.sip.sonars[1].range, 250);
  ASSERT_TRUE(parse.sip.io.has_value());
  ASSERT_TRUE(parse.sip.charge_state.has_value());  // written as zero before ROTVEL
  EXPECT_EQ(parse.sip.battery_decivolts_x10, 131);
  EXPECT_DOUBLE_EQ(parse.sip.battery_v(), 13.1);
  EXPECT_EQ(parse.sip.rot_vel_decideg_per_s, -455);
  EXPECT_EQ(parse.sip.fault_flags, 0x0F0F);
}

TEST(P3dxSipTest, TopBitOfPositionsIsIgnored) {
  Bytes payload = DecodeOne(kHandSip);
  payload[2] |= 0x80;  // XPOS high byte
  const P3dxSipParse parse = ParseP3dxStandardSip(payload);
  ASSERT_EQ(parse.status, P3dxSipStatus::kOk);
  EXPECT_EQ(parse.sip.x_pos, 1000);
}

TEST(P3dxSipTest, ShortAndForeignPacketsAreRejected) {
  const Bytes payload = DecodeOne(kHandSip);
  for (size_t size = 1; size < payload.size(); ++size) {
    const Bytes cut(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(size));
    EXPECT_EQ(ParseP3dxStandardSip(cut).status, P3dxSipStatus::kShort) << size;
  }
  Bytes announces_sonars = payload;
  announces_sonars[19] = 2;      // two sonar readings announced
  announces_sonars.push_back(1); // but only 4 of their 6 bytes present
  announces_sonars.push_back(0x10);
  announces_sonars.push_back(0x00);
  announces_sonars.push_back(2);
  EXPECT_EQ(ParseP3dxStandardSip(announces_sonars).status, P3dxSipStatus::kShort);
  EXPECT_EQ(ParseP3dxStandardSip({}).status, P3dxSipStatus::kNotSip);
  Bytes config = payload;
  config[0] = 0x20;
  EXPECT_EQ(ParseP3dxStandardSip(config).status, P3dxSipStatus::kNotSip);
}

TEST(P3dxSipTest, IncompleteOptionalGroupIsLeftOut) {
  Bytes payload = DecodeOne(kHandSip);
  payload.insert(payload.end(), {1, 2, 3});  // 3 of the 5 I/O bytes
  const P3dxSipParse parse = ParseP3dxStandardSip(payload);
  ASSERT_EQ(parse.status, P3dxSipStatus::kOk);
  EXPECT_FALSE(parse.sip.io.has_value());
}

TEST(P3dxSipTest, NamePacket) {
  // 02 "Robbie" 00 "Pioneer" 00 "P3DX-SH" 00
  Bytes payload = {0x02};
  for (const char* s : {"Robbie", "Pioneer", "P3DX-SH"}) {
    payload.insert(payload.end(), s, s + std::char_traits<char>::length(s));
    payload.push_back(0);
  }
  const auto identity = ParseP3dxRobotIdentity(payload);
  ASSERT_TRUE(identity.has_value());
  EXPECT_EQ(identity->name, "Robbie");
  EXPECT_EQ(identity->robot_class, "Pioneer");
  EXPECT_EQ(identity->subclass, "p3dx-sh");
  EXPECT_EQ(EncodeP3dxRobotIdentity({"Robbie", "Pioneer", "P3DX-SH"}), payload);
  EXPECT_FALSE(ParseP3dxRobotIdentity({0x32, 0x00}).has_value());
  const auto unterminated = ParseP3dxRobotIdentity({0x02, 'a', 0, 'b'});
  ASSERT_TRUE(unterminated.has_value());
  EXPECT_EQ(unterminated->robot_class, "b");
  EXPECT_EQ(unterminated->subclass, "");
}

TEST(P3dxOdometryTest, PositionDeltaWrapsModulo2To15) {
  EXPECT_EQ(P3dxPositionDelta(32760, 5), 13);
  EXPECT_EQ(P3dxPositionDelta(5, 32760), -13);
  EXPECT_EQ(P3dxPositionDelta(100, 200), 100);
  EXPECT_EQ(P3dxPositionDelta(0, 16383), 16383);
  EXPECT_EQ(P3dxPositionDelta(0, 16384), -16384);
}

TEST(P3dxOdometryTest, ConversionFromSubclass) {
  ASSERT_TRUE(P3dxConversionForSubclass("p3dx").has_value());
  EXPECT_DOUBLE_EQ(P3dxConversionForSubclass("p3dx")->dist_conv_mm, 0.485);
  EXPECT_DOUBLE_EQ(P3dxConversionForSubclass("p3dx-sh")->dist_conv_mm, 1.0);
  EXPECT_DOUBLE_EQ(P3dxConversionForSubclass("p3dx-sh-lms1xx")->dist_conv_mm, 1.0);
  EXPECT_FALSE(P3dxConversionForSubclass("p3at").has_value());
  EXPECT_NEAR(P3dxConversion{}.effective_track_m(), 0.357142857, 1e-9);
}

P3dxStandardSip Sip(uint16_t x, uint16_t y, int16_t th) {
  P3dxStandardSip sip;
  sip.x_pos = x;
  sip.y_pos = y;
  sip.th_pos = th;
  return sip;
}

TEST(P3dxOdometryTest, XposWrapGivesPlusThirteenUnits) {
  P3dxOdometryIntegrator odometry;  // p3dx: 0.485 mm per unit
  const P3dxOdometry first = odometry.Update(Sip(32760, 100, 0));
  EXPECT_DOUBLE_EQ(first.x_m, 0.0);
  EXPECT_DOUBLE_EQ(first.y_m, 0.0);
  EXPECT_DOUBLE_EQ(first.heading_rad, 0.0);
  const P3dxOdometry second = odometry.Update(Sip(5, 100, 0));
  EXPECT_NEAR(second.x_m, 13 * 0.485e-3, 1e-12);
  EXPECT_NEAR(second.y_m, 0.0, 1e-12);
  const P3dxOdometry third = odometry.Update(Sip(32760, 100, 0));  // and back
  EXPECT_NEAR(third.x_m, 0.0, 1e-12);
}

TEST(P3dxOdometryTest, ThposWrapsModulo4096) {
  P3dxOdometryIntegrator odometry;
  odometry.Update(Sip(0, 0, 4094));
  const P3dxOdometry across = odometry.Update(Sip(0, 0, 2));  // +4 units across the wrap
  EXPECT_NEAR(across.heading_rad, 4 * 2 * kPi / 4096, 1e-12);
  // A firmware that sends signed THPOS: -2 is the same angle as 4094.
  P3dxOdometryIntegrator signed_odometry;
  signed_odometry.Update(Sip(0, 0, -2));
  EXPECT_NEAR(signed_odometry.Update(Sip(0, 0, 2)).heading_rad, 4 * 2 * kPi / 4096, 1e-12);
  EXPECT_NEAR(P3dxHeadingRad(2048, P3dxConversion{}), kPi, 1e-12);   // (-pi, pi]
  EXPECT_NEAR(P3dxHeadingRad(-2048, P3dxConversion{}), kPi, 1e-12);
  EXPECT_NEAR(P3dxHeadingRad(1024, P3dxConversion{}), kPi / 2, 1e-12);
}

TEST(P3dxOdometryTest, PoseStartsAtZeroAndFollowsTheFirmwareFrame) {
  P3dxOdometryIntegrator odometry(*P3dxConversionForSubclass("p3dx-sh"));  // 1 mm per unit
  odometry.Update(Sip(1000, 1000, 1024));  // firmware heading +90 degrees: ours 0
  // The firmware moves +100 mm along its y axis, i.e. straight ahead: our +x.
  const P3dxOdometry moved = odometry.Update(Sip(1000, 1100, 1024));
  EXPECT_NEAR(moved.x_m, 0.1, 1e-12);
  EXPECT_NEAR(moved.y_m, 0.0, 1e-12);
  EXPECT_NEAR(moved.heading_rad, 0.0, 1e-12);
}

TEST(P3dxOdometryTest, ReanchorKeepsThePoseContinuous) {
  P3dxOdometryIntegrator odometry(*P3dxConversionForSubclass("p3dx-sh"));
  odometry.Update(Sip(0, 0, 0));
  const P3dxOdometry before = odometry.Update(Sip(500, 0, 1024));  // 0.5 m ahead, turned left
  odometry.Reanchor();
  // New session: the firmware reset its counters to zero.
  const P3dxOdometry anchor = odometry.Update(Sip(0, 0, 0));
  EXPECT_DOUBLE_EQ(anchor.x_m, before.x_m);
  EXPECT_DOUBLE_EQ(anchor.y_m, before.y_m);
  EXPECT_NEAR(anchor.heading_rad, before.heading_rad, 1e-12);
  // Forward in the firmware's new frame (+x) is +y in ours (we face +90 degrees).
  const P3dxOdometry after = odometry.Update(Sip(200, 0, 0));
  EXPECT_NEAR(after.x_m, 0.5, 1e-12);
  EXPECT_NEAR(after.y_m, 0.2, 1e-12);
}

TEST(P3dxOdometryTest, VelocitiesFromWheelsAndRotvel) {
  P3dxOdometryIntegrator odometry;
  P3dxStandardSip sip = Sip(0, 0, 0);
  sip.left_vel = 100;
  sip.right_vel = 300;
  const P3dxOdometry from_wheels = odometry.Update(sip);
  EXPECT_DOUBLE_EQ(from_wheels.left_wheel_velocity_mps, 0.1);
  EXPECT_DOUBLE_EQ(from_wheels.right_wheel_velocity_mps, 0.3);
  EXPECT_DOUBLE_EQ(from_wheels.linear_velocity_mps, 0.2);
  EXPECT_NEAR(from_wheels.angular_velocity_radps, 0.2 / (2.0 / 0.0056 / 1000.0), 1e-12);  // 0.56
  sip.rot_vel_decideg_per_s = 300;  // 30 deg/s
  EXPECT_NEAR(odometry.Update(sip).angular_velocity_radps, 30.0 * kPi / 180.0, 1e-12);
}

}  // namespace
}  // namespace slammtt
