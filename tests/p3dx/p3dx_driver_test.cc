// The driver against the emulated robot in simulated time: handshake, commands, timeouts,
// faults and reconnection. No sleeping, no sockets: every wait advances a simulated clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "common/angle.h"
#include "drivers/p3dx/p3dx_commands.h"
#include "drivers/p3dx/p3dx_driver.h"
#include "simulated_robot_link.h"

namespace slammtt {
namespace {

constexpr double kPi = 3.14159265358979323846;
namespace cmd = p3dx_command;

// The driver, the emulated robot and the simulated clock, with helpers to run them.
class DriverBench {
 public:
  void Start(const P3dxRobotModelOptions& robot_options = P3dxRobotModelOptions{},
             double bytes_per_second = 960.0) {
    robot_ = std::make_unique<SimulatedRobot>(robot_options, &clock_, bytes_per_second);
    options_.port = "/dev/ttyUSB0";
    driver_ = std::make_unique<P3dxDriver>(
        options_,
        [this](const std::string& endpoint, int baud) { return robot_->Open(endpoint, baud); },
        &clock_, &sink_);
  }

  // Runs the driver's loop for `seconds` of simulated time, calling `each` every iteration.
  void RunFor(double seconds, const std::function<void()>& each = {}) {
    const int64_t end = clock_.now_us + static_cast<int64_t>(seconds * 1e6);
    while (clock_.now_us < end) {
      const int64_t before = clock_.now_us;
      driver_->Poll(10);
      if (each) each();
      if (clock_.now_us == before) clock_.now_us += 1000;
      robot_->Sync();
    }
  }

  // Runs the driver as slammtt-p3dx does: Poll(0), then one wait until the driver's next timer
  // (MillisecondsUntilDue) or, while a link is open, until bytes reach it (the robot's next
  // event stands in for the link's poll descriptor becoming readable). Returns how many waits
  // moved the clock.
  int64_t RunAsProcessFor(double seconds, const std::function<void()>& each = {}) {
    const int64_t end = clock_.now_us + static_cast<int64_t>(seconds * 1e6);
    int64_t wakeups = 0;
    int turns_without_time = 0;
    while (clock_.now_us < end) {
      driver_->Poll(0);
      if (each) each();
      robot_->Sync();
      const int64_t due_us = clock_.now_us + int64_t{driver_->MillisecondsUntilDue()} * 1000;
      const int64_t input_us =
          driver_->link_open() ? robot_->NextEventUs() : std::numeric_limits<int64_t>::max();
      const int64_t wake_us = std::min({due_us, input_us, end});
      if (wake_us <= clock_.now_us) {
        // Due now (or bytes waiting beyond one read): the next Poll(0) must deal with it; a
        // timer it leaves due would spin the process.
        if (++turns_without_time > 20) {
          ADD_FAILURE() << "the loop spins at t = " << clock_.now_us << " us in state "
                        << P3dxDriver::StateName(driver_->state());
          return wakeups;
        }
        continue;
      }
      turns_without_time = 0;
      clock_.now_us = wake_us;
      ++wakeups;
    }
    return wakeups;
  }

  // Sends a velocity command every 100 ms of simulated time while running.
  std::function<void()> CommandsAt10Hz(double linear_mps, double angular_radps) {
    auto next = std::make_shared<int64_t>(clock_.now_us);
    return [this, next, linear_mps, angular_radps] {
      if (clock_.now_us >= *next) {
        Command(linear_mps, angular_radps);
        *next += 100000;
      }
    };
  }

  void Command(double linear_mps, double angular_radps) {
    slammtt_msgs::velocity_command_t command{};
    command.utime = clock_.NowUtime();
    command.linear_mps = linear_mps;
    command.angular_radps = angular_radps;
    last_command_us_ = clock_.now_us;
    driver_->HandleVelocityCommand(command);
  }

  // The commands the robot received, in order, as (number, value, connected).
  std::vector<P3dxReceivedCommand> Received() const { return robot_->model().received(); }

  static bool Is(const P3dxReceivedCommand& r, uint8_t number, bool connected) {
    return r.command.number == number && r.connected == connected;
  }

  SimulatedClock clock_;
  std::unique_ptr<SimulatedRobot> robot_;
  RecordingSink sink_;
  P3dxDriverOptions options_;
  std::unique_ptr<P3dxDriver> driver_;
  int64_t last_command_us_ = 0;
};

class P3dxDriverTest : public ::testing::Test, public DriverBench {};

TEST_F(P3dxDriverTest, HandshakeSyncsOpensEnablesAndStreamsOdometry) {
  Start();
  RunFor(2.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const auto received = Received();
  ASSERT_GE(received.size(), 6u);
  EXPECT_TRUE(Is(received[0], cmd::kVel2, false));  // the stop before every SYNC0
  EXPECT_EQ(received[0].command.value, 0);
  EXPECT_TRUE(Is(received[1], cmd::kSync0, false));
  EXPECT_TRUE(Is(received[2], cmd::kSync1, false));
  EXPECT_TRUE(Is(received[3], cmd::kSync2, false));
  EXPECT_TRUE(Is(received[4], cmd::kOpen, false));
  EXPECT_TRUE(Is(received[5], cmd::kEnable, true));
  EXPECT_EQ(received[5].command.value, 1);
  EXPECT_TRUE(robot_->model().motors_enabled());
  // About one ODOMETRY per SIP (10 Hz) since the session opened.
  EXPECT_GE(sink_.odometry.size(), 18u);
  EXPECT_EQ(static_cast<int64_t>(sink_.odometry.size()), robot_->model().sips_sent());
  for (size_t i = 0; i < sink_.odometry.size(); ++i) {
    EXPECT_EQ(sink_.odometry[i].sequence, static_cast<int64_t>(i));
    if (i > 0) {
      EXPECT_GT(sink_.odometry[i].utime, sink_.odometry[i - 1].utime);
    }
  }
  const auto status = driver_->Status();
  EXPECT_TRUE(status.connected);
  EXPECT_EQ(status.state, "running");
  EXPECT_EQ(status.robot_name, "slammtt-emulator");
  EXPECT_EQ(status.robot_class, "Pioneer");
  EXPECT_EQ(status.robot_subclass, "p3dx");
  EXPECT_DOUBLE_EQ(status.battery_v, 12.5);
  EXPECT_TRUE(status.motors_enabled);
  EXPECT_EQ(status.checksum_errors, 0);
  EXPECT_EQ(status.short_packets, 0);
  EXPECT_EQ(sink_.undecodable, 0);
}

TEST_F(P3dxDriverTest, OdometryUtimeIsTheHostTimeOfArrival) {
  Start();
  int64_t checked = 0;
  RunFor(1.5, [&] {
    if (!sink_.odometry.empty() && sink_.odometry.size() > static_cast<size_t>(checked)) {
      // Published during this iteration: its utime is the wall clock now (the last byte of the
      // SIP was read in this very Poll, and simulated time only moves inside reads).
      EXPECT_EQ(sink_.odometry.back().utime, clock_.NowUtime());
      checked = static_cast<int64_t>(sink_.odometry.size());
    }
  });
  EXPECT_GT(checked, 5);
}

class P3dxDriverSubclassTest : public P3dxDriverTest,
                               public ::testing::WithParamInterface<const char*> {};

TEST_P(P3dxDriverSubclassTest, ConversionFactorsFollowTheSubclass) {
  P3dxRobotModelOptions robot;
  robot.identity.subclass = GetParam();
  Start(robot);
  RunFor(1.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  // 0.4 m/s for 5 s: 2 m, in XPOS units of 0.485 mm (p3dx) or 1 mm (p3dx-sh).
  RunFor(5.0, CommandsAt10Hz(0.4, 0.0));
  RunFor(1.0);  // stops by command timeout
  const double robot_x_m = robot_->model().x_mm() / 1000.0;
  ASSERT_GT(robot_x_m, 1.5);
  ASSERT_FALSE(sink_.odometry.empty());
  // One XPOS unit of rounding.
  EXPECT_NEAR(sink_.odometry.back().x_m, robot_x_m,
              robot_->model().conversion().dist_conv_mm / 1000.0);
  EXPECT_NEAR(sink_.odometry.back().y_m, 0.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Subclasses, P3dxDriverSubclassTest, ::testing::Values("p3dx", "p3dx-sh"));

TEST_F(P3dxDriverTest, OdometryFollowsTheRobotAcrossTheXposWrap) {
  P3dxRobotModelOptions robot;
  robot.max_linear_mps = 1.5;
  Start(robot, 0.0);
  options_.max_linear_mps = 1.2;
  driver_ = std::make_unique<P3dxDriver>(
      options_, [this](const std::string& e, int b) { return robot_->Open(e, b); }, &clock_, &sink_);
  RunFor(1.0);
  // 1.2 m/s for 15 s = 18 m > 32768 * 0.485 mm = 15.9 m: XPOS wraps once.
  RunFor(15.0, CommandsAt10Hz(1.2, 0.0));
  const double robot_x_m = robot_->model().x_mm() / 1000.0;
  ASSERT_GT(robot_x_m, 16.0);
  EXPECT_NEAR(sink_.odometry.back().x_m, robot_x_m, 0.001);
}

TEST_F(P3dxDriverTest, VelocityCommandsAreClampedAndSentAsVelAndRvel) {
  Start();
  RunFor(1.0);
  Command(0.3, 0.5);
  RunFor(0.05);
  auto received = Received();
  ASSERT_GE(received.size(), 2u);
  const auto& vel = received[received.size() - 2];
  const auto& rvel = received[received.size() - 1];
  EXPECT_TRUE(Is(vel, cmd::kVel, true));
  EXPECT_EQ(vel.command.value, 300);
  EXPECT_TRUE(Is(rvel, cmd::kRvel, true));
  EXPECT_EQ(rvel.command.value, 29);  // 0.5 rad/s = 28.6 deg/s
  EXPECT_NEAR(0.5 * (robot_->model().left_wheel_mmps() + robot_->model().right_wheel_mmps()), 300.0,
              1e-9);

  Command(5.0, -9.0);  // beyond the limits (0.5 m/s, 1.0 rad/s)
  RunFor(0.05);
  received = Received();
  EXPECT_EQ(received[received.size() - 2].command.value, 500);
  EXPECT_EQ(received[received.size() - 1].command.value, -57);  // -1 rad/s = -57.3 deg/s

  Command(-0.25, 0.0);
  RunFor(0.05);
  received = Received();
  EXPECT_EQ(received[received.size() - 2].command.value, -250);
}

TEST_F(P3dxDriverTest, NonFiniteCommandsAreSkippedAndCounted) {
  Start();
  RunFor(1.0);
  const size_t before = Received().size();
  Command(std::numeric_limits<double>::quiet_NaN(), 0.0);
  Command(0.1, std::numeric_limits<double>::infinity());
  EXPECT_EQ(driver_->commands_skipped(), 2);
  EXPECT_EQ(Received().size(), before);
  EXPECT_FALSE(driver_->Status().last_error.empty());
}

// Commands from the bus (ReceiveVelocityCommand): what slammtt-p3dx hands every VELOCITY_COMMAND.
class P3dxCommandAuthTest : public P3dxDriverTest {
 protected:
  static CommandKey Key(uint8_t seed) {
    CommandKey key{};
    for (size_t k = 0; k < key.size(); ++k) key[k] = static_cast<uint8_t>(seed * 7 + k);
    return key;
  }
  slammtt_msgs::velocity_command_t Unsigned(double linear_mps) {
    slammtt_msgs::velocity_command_t command{};
    command.utime = clock_.NowUtime();
    command.linear_mps = linear_mps;
    return command;
  }
  slammtt_msgs::velocity_command_t SignedBy(VelocityCommandSigner* signer, double linear_mps,
                                            int64_t utime_offset_us = 0) {
    slammtt_msgs::velocity_command_t command = Unsigned(linear_mps);
    command.utime += utime_offset_us;
    signer->Sign(&command);
    return command;
  }
  double Speed() const {
    return 0.5 * (robot_->model().left_wheel_mmps() + robot_->model().right_wheel_mmps());
  }
};

TEST_F(P3dxCommandAuthTest, WithoutAKeyNoCommandMovesTheRobot) {
  Start();
  RunFor(1.0);
  VelocityCommandSigner signer(Key(1), "VELOCITY_COMMAND", 11);
  for (int k = 0; k < 10; ++k) {
    driver_->ReceiveVelocityCommand(Unsigned(0.4));
    driver_->ReceiveVelocityCommand(SignedBy(&signer, 0.4));
    RunFor(0.1);
    ASSERT_EQ(Speed(), 0.0);
  }
  const slammtt_msgs::base_status_t status = driver_->Status();
  EXPECT_EQ(status.command_auth, "hmac-sha256 without a key: every command refused");
  EXPECT_EQ(status.commands_unauthenticated, 20);
  EXPECT_EQ(status.commands_accepted, 0);
}

TEST_F(P3dxCommandAuthTest, OnlyFreshSignedCommandsWithTheRobotsKeyMoveIt) {
  Start();
  driver_->SetCommandKey(Key(1));
  RunFor(1.0);
  VelocityCommandSigner base_station(Key(1), "VELOCITY_COMMAND", 11);
  VelocityCommandSigner stranger(Key(2), "VELOCITY_COMMAND", 12);
  VelocityCommandSigner other_channel(Key(1), "VELOCITY_COMMAND_2", 13);

  // 40 unsigned commands at 10 Hz (the issue's attack), forged and foreign ones: nothing moves.
  for (int k = 0; k < 40; ++k) {
    driver_->ReceiveVelocityCommand(Unsigned(0.4));
    RunFor(0.1);
    ASSERT_EQ(Speed(), 0.0);
  }
  slammtt_msgs::velocity_command_t forged = SignedBy(&base_station, 0.1);
  forged.linear_mps = 0.4;
  driver_->ReceiveVelocityCommand(forged);
  driver_->ReceiveVelocityCommand(SignedBy(&stranger, 0.4));
  driver_->ReceiveVelocityCommand(SignedBy(&other_channel, 0.4));
  // Signed with the key, but 2 s old or 2 s ahead of the robot's clock (window 1 s).
  driver_->ReceiveVelocityCommand(SignedBy(&base_station, 0.4, -2000000));
  driver_->ReceiveVelocityCommand(SignedBy(&base_station, 0.4, 2000000));
  RunFor(0.2);
  EXPECT_EQ(Speed(), 0.0);

  // The base station drives it.
  const slammtt_msgs::velocity_command_t good = SignedBy(&base_station, 0.3);
  driver_->ReceiveVelocityCommand(good);
  RunFor(0.05);
  EXPECT_NEAR(Speed(), 300.0, 1e-9);
  // Played back: refused; the robot stops at the command timeout as if nothing came.
  for (int k = 0; k < 10; ++k) {
    driver_->ReceiveVelocityCommand(good);
    RunFor(0.1);
  }
  EXPECT_EQ(Speed(), 0.0);

  const slammtt_msgs::base_status_t status = driver_->Status();
  EXPECT_EQ(status.command_auth, "hmac-sha256");
  EXPECT_EQ(status.commands_accepted, 1);
  EXPECT_EQ(status.commands_unauthenticated, 43);
  EXPECT_EQ(status.commands_stale, 2);
  EXPECT_EQ(status.commands_replayed, 10);
  EXPECT_EQ(driver_->commands_refused(), 55);
}

TEST_F(P3dxCommandAuthTest, UnauthenticatedSetupTakesEveryCommand) {
  options_.command_authentication = P3dxDriverOptions::CommandAuthentication::kNone;
  Start();
  RunFor(1.0);
  driver_->ReceiveVelocityCommand(Unsigned(0.2));
  RunFor(0.05);
  EXPECT_NEAR(Speed(), 200.0, 1e-9);
  EXPECT_EQ(driver_->Status().command_auth, "none (local only)");
  EXPECT_EQ(driver_->Status().commands_accepted, 1);
}

TEST_F(P3dxDriverTest, StopsWhenCommandsStopArriving) {
  options_.command_timeout_s = 0.5;
  Start();
  RunFor(1.0);
  RunFor(1.0, CommandsAt10Hz(0.3, 0.0));
  ASSERT_TRUE(robot_->model().moving());
  const int64_t last_command = last_command_us_;
  int64_t stopped_at = -1;
  RunFor(1.0, [&] {
    if (stopped_at < 0 && !robot_->model().moving()) stopped_at = clock_.now_us;
  });
  ASSERT_GE(stopped_at, 0);
  // The robot sees velocity 0 within the configured time (plus one 10 ms wait in Read).
  EXPECT_LE(stopped_at - last_command, 500000 + 10000);
  EXPECT_GE(stopped_at - last_command, 500000);
  const auto received = Received();
  bool saw_vel0 = false;
  for (const auto& r : received) {
    if (r.time_us > last_command && r.command.number == cmd::kVel && r.command.value == 0) saw_vel0 = true;
  }
  EXPECT_TRUE(saw_vel0);
  EXPECT_TRUE(driver_->Status().command_timeout_stop);
  EXPECT_EQ(robot_->model().watchdog_stops(), 0);
  // A new command clears the flag and moves the robot again.
  Command(0.2, 0.0);
  RunFor(0.05);
  EXPECT_FALSE(driver_->Status().command_timeout_stop);
  EXPECT_TRUE(robot_->model().moving());
}

TEST_F(P3dxDriverTest, FirmwareWatchdogStaysFedWhileCommandsArrive) {
  Start();
  RunFor(1.0);
  bool ever_stopped = false;
  bool started = false;
  RunFor(5.0, [&, commands = CommandsAt10Hz(0.25, 0.0)] {
    commands();
    if (robot_->model().moving()) started = true;
    if (started && !robot_->model().moving()) ever_stopped = true;
  });
  EXPECT_TRUE(started);
  EXPECT_FALSE(ever_stopped);
  EXPECT_EQ(robot_->model().watchdog_stops(), 0);
  EXPECT_NEAR(robot_->model().x_mm(), 250.0 * 5.0, 30.0);
}

TEST_F(P3dxDriverTest, IdleSessionIsKeptAliveWithPulses) {
  Start();
  RunFor(1.0);
  const size_t first = Received().size();
  RunFor(10.0);
  const auto received = Received();
  ASSERT_GT(received.size(), first + 15);
  int64_t previous = received[first - 1].time_us;
  for (size_t i = first; i < received.size(); ++i) {
    EXPECT_TRUE(Is(received[i], cmd::kPulse, true));
    EXPECT_LE(received[i].time_us - previous, 510000);
    previous = received[i].time_us;
  }
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
}

TEST_F(P3dxDriverTest, RobotLeftMovingByAnEarlierClientIsStoppedThenClosedThenResynced) {
  Start();
  robot_->model().StartConnected(0.3, 0.0, clock_.now_us);
  RunFor(3.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const auto received = Received();
  // VEL2 0 ahead of SYNC0 (which the open session takes as a keep-alive) stops it at once, the
  // driver's VEL2 0 while it still reports moving, CLOSE once it reported stopped, then a
  // fresh handshake (behind its own VEL2 0).
  size_t i = 0;
  ASSERT_TRUE(Is(received[i], cmd::kVel2, true));
  EXPECT_EQ(received[i++].command.value, 0);
  ASSERT_TRUE(Is(received[i++], cmd::kSync0, true));
  while (i < received.size() && Is(received[i], cmd::kVel2, true)) {
    EXPECT_EQ(received[i].command.value, 0);
    ++i;
  }
  ASSERT_LT(i, received.size());
  EXPECT_TRUE(Is(received[i], cmd::kClose, true));
  while (i < received.size() && Is(received[i], cmd::kClose, true)) ++i;
  ASSERT_LT(i + 5, received.size());
  EXPECT_TRUE(Is(received[i], cmd::kVel2, false));
  EXPECT_TRUE(Is(received[i + 1], cmd::kSync0, false));
  EXPECT_TRUE(Is(received[i + 2], cmd::kSync1, false));
  EXPECT_TRUE(Is(received[i + 3], cmd::kSync2, false));
  EXPECT_TRUE(Is(received[i + 4], cmd::kOpen, false));
  EXPECT_FALSE(robot_->model().moving());
  EXPECT_EQ(robot_->model().watchdog_stops(), 0);
}

TEST_F(P3dxDriverTest, StoppedRobotInAnEarlierSessionIsClosedThenResynced) {
  Start();
  robot_->model().StartConnected(0.0, 0.0, clock_.now_us);
  RunFor(3.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const auto received = Received();
  ASSERT_GE(received.size(), 8u);
  EXPECT_TRUE(Is(received[0], cmd::kVel2, true));
  EXPECT_TRUE(Is(received[1], cmd::kSync0, true));
  EXPECT_TRUE(Is(received[2], cmd::kClose, true));
  EXPECT_TRUE(Is(received[3], cmd::kVel2, false));
  EXPECT_TRUE(Is(received[4], cmd::kSync0, false));
  EXPECT_TRUE(Is(received[7], cmd::kOpen, false));
}

TEST_F(P3dxDriverTest, UnansweredSyncIsResentThenTheLinkIsReopened) {
  Start();
  robot_->model().SilenceFor(6000000, clock_.now_us);  // a robot that is off for 6 s
  RunFor(10.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  EXPECT_GE(robot_->opens(), 2);  // 8 unanswered SYNC0 in 4 s, reopen after the backoff
  EXPECT_NE(driver_->Status().last_error.find("no reply to SYNC0"), std::string::npos);
}

// Checks that no ODOMETRY came from a damaged packet: no step jumps, and once the robot has
// stopped (the caller let the command timeout stop it) the last one equals the robot's pose to
// within a unit of rounding -- unless a reconnection lost the motion in between.
void ExpectOdometryTracksTheRobot(const RecordingSink& sink, SimulatedRobot& robot,
                                  bool same_frame = true) {
  ASSERT_FALSE(sink.odometry.empty());
  ASSERT_FALSE(robot.model().moving());
  if (same_frame) {
    EXPECT_NEAR(sink.odometry.back().x_m, robot.model().x_mm() / 1000.0, 0.002);
    EXPECT_NEAR(sink.odometry.back().y_m, robot.model().y_mm() / 1000.0, 0.002);
    // One THPOS unit (2 pi / 4096 rad) of rounding.
    EXPECT_NEAR(WrapAngle(sink.odometry.back().heading_rad - robot.model().heading_rad()), 0.0,
                0.0016);
  }
  for (size_t i = 1; i < sink.odometry.size(); ++i) {
    // A step never jumps further than 0.3 m/s allows in 0.5 s (a bad packet would).
    const double dx = sink.odometry[i].x_m - sink.odometry[i - 1].x_m;
    const double dy = sink.odometry[i].y_m - sink.odometry[i - 1].y_m;
    EXPECT_LT(std::hypot(dx, dy), 0.15) << i;
  }
}

TEST_F(P3dxDriverTest, GarbageBytesAreSkippedWithoutOdometry) {
  Start();
  RunFor(1.0);
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  RunFor(3.0, [&, commands = CommandsAt10Hz(0.3, 0.0), n = 0]() mutable {
    commands();
    if (++n % 50 == 0) robot_->model().InjectGarbage(40);
  });
  RunFor(1.5);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const int64_t sips = robot_->model().sips_sent() - sips_before;
  const int64_t odometry = static_cast<int64_t>(sink_.odometry.size() - odometry_before);
  // Garbage can hide at most the SIP it lands in front of (a false header swallowing it is
  // re-scanned, so normally none is lost).
  EXPECT_GE(odometry, sips - 3);
  EXPECT_LE(odometry, sips);
  EXPECT_GE(driver_->decoder_counters().bytes_skipped, 40 * 5);  // the garbage went through
  ExpectOdometryTracksTheRobot(sink_, *robot_);
}

TEST_F(P3dxDriverTest, BadChecksumsAreCountedAndGiveNoOdometry) {
  Start();
  RunFor(1.0);
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  robot_->model().CorruptNextChecksums(5);
  RunFor(2.0, CommandsAt10Hz(0.2, 0.3));
  RunFor(1.5);
  const auto status = driver_->Status();
  EXPECT_EQ(status.checksum_errors, 5);
  EXPECT_EQ(static_cast<int64_t>(sink_.odometry.size() - odometry_before),
            robot_->model().sips_sent() - sips_before - 5);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  ExpectOdometryTracksTheRobot(sink_, *robot_);
}

TEST_F(P3dxDriverTest, DroppedBytesCostOnlyTheDamagedPackets) {
  Start();
  RunFor(1.0);
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  robot_->model().DropNextBytes(3);
  RunFor(2.0, CommandsAt10Hz(0.2, 0.0));
  RunFor(1.5);
  const int64_t lost = robot_->model().sips_sent() - sips_before -
                       static_cast<int64_t>(sink_.odometry.size() - odometry_before);
  EXPECT_GE(lost, 1);
  EXPECT_LE(lost, 2);  // the damaged SIP, and at most the one its false frame swallowed
  const auto status = driver_->Status();
  EXPECT_GE(status.checksum_errors + status.short_packets, 1);
  ExpectOdometryTracksTheRobot(sink_, *robot_);
}

TEST_F(P3dxDriverTest, ShortSipsAreCountedAndGiveNoOdometry) {
  Start();
  RunFor(1.0);
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  robot_->model().SendShortSips(4);
  RunFor(2.0, CommandsAt10Hz(0.2, 0.0));
  RunFor(1.5);
  EXPECT_EQ(driver_->Status().short_packets, 4);
  EXPECT_EQ(driver_->Status().checksum_errors, 0);
  EXPECT_EQ(static_cast<int64_t>(sink_.odometry.size() - odometry_before),
            robot_->model().sips_sent() - sips_before - 4);
  ExpectOdometryTracksTheRobot(sink_, *robot_);
}

TEST_F(P3dxDriverTest, TruncatedPacketsAreSkipped) {
  Start();
  RunFor(1.0);
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  robot_->model().TruncateNextPackets(3);
  RunFor(2.0, CommandsAt10Hz(0.2, 0.0));
  RunFor(1.5);
  const int64_t lost = robot_->model().sips_sent() - sips_before -
                       static_cast<int64_t>(sink_.odometry.size() - odometry_before);
  EXPECT_GE(lost, 3);
  EXPECT_LE(lost, 6);
  EXPECT_GE(driver_->Status().checksum_errors + driver_->Status().short_packets, 3);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  ExpectOdometryTracksTheRobot(sink_, *robot_);
}

TEST_F(P3dxDriverTest, SilentRobotIsReportedAndReconnectedWithTheFullHandshake) {
  Start();
  RunFor(1.0);
  RunFor(1.0, CommandsAt10Hz(0.2, 0.0));
  robot_->model().SilenceFor(3000000, clock_.now_us);
  bool saw_lost = false;
  RunFor(8.0, [&, commands = CommandsAt10Hz(0.2, 0.0)] {
    commands();
    if (driver_->state() == P3dxDriver::State::kDisconnected) saw_lost = true;
  });
  EXPECT_TRUE(robot_->model().moving());  // commands resumed after the reconnection
  RunFor(1.5);
  EXPECT_TRUE(saw_lost);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const auto status = driver_->Status();
  EXPECT_EQ(status.reconnects, 1);
  EXPECT_NE(status.last_error.find("no valid SIP"), std::string::npos);
  // The robot's own watchdog stopped it while it heard nothing; the driver then found its old
  // session open, closed it and synced again.
  EXPECT_EQ(robot_->model().watchdog_stops(), 1);
  bool closed_then_synced = false;
  const auto received = Received();
  for (size_t i = 0; i + 2 < received.size(); ++i) {
    // CLOSE, then the stop that precedes every SYNC0, then SYNC0.
    if (Is(received[i], cmd::kClose, true) && received[i + 1].command.number == cmd::kVel2 &&
        Is(received[i + 2], cmd::kSync0, false)) {
      closed_then_synced = true;
    }
  }
  EXPECT_TRUE(closed_then_synced);
  ExpectOdometryTracksTheRobot(sink_, *robot_, /*same_frame=*/false);
}

// A robot that goes quiet but still hears (its transmit line failed): after the SIP timeout the
// driver resyncs, and a SYNC0 that reaches the still-open session is only a keep-alive to it.
// Before: those SYNC0 retries fed the watchdog and the robot drove on at its last speed for
// 6.5 s after it went quiet (2.6 m at 0.4 m/s). Now a stop (VEL2 0) goes out when the link is
// given up and before every SYNC0.
TEST_F(P3dxDriverTest, AQuietRobotThatStillHearsIsStoppedBeforeEveryResync) {
  Start();
  RunFor(1.0);
  RunFor(1.0, CommandsAt10Hz(0.4, 0.0));
  ASSERT_TRUE(robot_->model().moving());
  const int64_t quiet_from = clock_.now_us;
  const size_t received_before = Received().size();
  robot_->model().MuteFor(20000000, clock_.now_us);
  int64_t stopped_at = -1;
  // The planner goes on asking for 0.4 m/s: only the driver can know the robot is lost.
  RunFor(10.0, [&, commands = CommandsAt10Hz(0.4, 0.0)] {
    commands();
    if (stopped_at < 0 && !robot_->model().moving()) stopped_at = clock_.now_us;
  });
  ASSERT_GE(stopped_at, 0) << "still moving 10 s after the robot went quiet";
  // The SIP timeout (1 s) and one poll: never a SYNC0 keep-alive first.
  EXPECT_LE(stopped_at - quiet_from, 1100000);
  EXPECT_EQ(robot_->model().watchdog_stops(), 0);
  const auto received = Received();
  int syncs = 0;
  for (size_t i = received_before; i < received.size(); ++i) {
    if (received[i].command.number != cmd::kSync0) continue;
    ++syncs;
    ASSERT_GT(i, received_before);
    EXPECT_EQ(received[i - 1].command.number, cmd::kVel2) << "SYNC0 #" << syncs;
    EXPECT_EQ(received[i - 1].command.value, 0);
  }
  EXPECT_GE(syncs, 8);
}

TEST_F(P3dxDriverTest, UnpluggedLinkIsReopenedWithBackoff) {
  Start();
  RunFor(1.0);
  robot_->Unplug();
  RunFor(5.0);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kDisconnected);
  const int opens_while_unplugged = robot_->opens();
  // Backoff 0.5, 1, 2, 4 s: 3 to 4 failed attempts in 5 s, not one per poll.
  EXPECT_GE(opens_while_unplugged, 3);
  EXPECT_LE(opens_while_unplugged, 5);
  EXPECT_EQ(driver_->Status().state, "reconnecting");
  robot_->Plug();
  RunFor(10.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  EXPECT_EQ(driver_->Status().reconnects, 1);
  for (const auto& endpoint : robot_->opened_endpoints) EXPECT_EQ(endpoint, "/dev/ttyUSB0");
}

TEST_F(P3dxDriverTest, OdometryIsContinuousAcrossAReconnection) {
  Start();
  RunFor(1.0);
  RunFor(2.0, CommandsAt10Hz(0.3, 0.2));
  robot_->Unplug();
  RunFor(0.7);
  robot_->Plug();
  RunFor(3.0, CommandsAt10Hz(0.3, 0.2));
  ASSERT_EQ(driver_->Status().reconnects, 1);
  for (size_t i = 1; i < sink_.odometry.size(); ++i) {
    const double step = std::hypot(sink_.odometry[i].x_m - sink_.odometry[i - 1].x_m,
                                   sink_.odometry[i].y_m - sink_.odometry[i - 1].y_m);
    EXPECT_LT(step, 0.2) << i;
  }
}

TEST_F(P3dxDriverTest, AStaleCommandDoesNotMoveTheRobotAfterAReconnection) {
  Start();
  RunFor(1.0);
  RunFor(1.0, CommandsAt10Hz(0.3, 0.0));
  robot_->Unplug();  // commands stop while the link is down
  RunFor(1.0);
  robot_->Plug();
  // The robot may still roll from the old session (its watchdog or our stale-session stop ends
  // that); once the new session runs it must stand still.
  bool moved_in_new_session = false;
  RunFor(5.0, [&] {
    if (driver_->state() == P3dxDriver::State::kRunning && robot_->model().moving()) {
      moved_in_new_session = true;
    }
  });
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  EXPECT_FALSE(moved_in_new_session);
  // After the new OPEN the robot heard no VEL but zeros (the old session's stop by its own
  // watchdog does not count).
  const auto received = Received();
  size_t open_index = 0;
  for (size_t i = 0; i < received.size(); ++i) {
    if (received[i].command.number == cmd::kOpen && !received[i].connected) open_index = i;
  }
  ASSERT_GT(open_index, 0u);
  for (size_t i = open_index; i < received.size(); ++i) {
    if (received[i].command.number == cmd::kVel || received[i].command.number == cmd::kRvel) {
      EXPECT_EQ(received[i].command.value, 0);
    }
  }
}

TEST_F(P3dxDriverTest, BumperAndStallFlagsReachBaseStatus) {
  Start();
  RunFor(1.0);
  robot_->model().SetBumpers(0x05, 0x40);
  robot_->model().SetWheelStall(false, true);
  const size_t before = sink_.status.size();
  RunFor(0.3);
  ASSERT_GT(sink_.status.size(), before);  // published on the change, not a second later
  const auto& status = sink_.status.back();
  EXPECT_EQ(status.bumpers, 0x05 | (0x40 << 8));
  EXPECT_FALSE(status.left_wheel_stall);
  EXPECT_TRUE(status.right_wheel_stall);
}

TEST_F(P3dxDriverTest, BaseStatusAboutOncePerSecond) {
  Start();
  RunFor(1.0);
  const size_t before = sink_.status.size();
  RunFor(10.0);
  const size_t published = sink_.status.size() - before;
  EXPECT_GE(published, 9u);
  EXPECT_LE(published, 11u);
}

TEST_F(P3dxDriverTest, ShutdownStopsTheRobotAndClosesTheSession) {
  Start();
  RunFor(1.0);
  RunFor(1.0, CommandsAt10Hz(0.3, 0.1));
  ASSERT_TRUE(robot_->model().moving());
  driver_->Shutdown();
  robot_->Sync();
  EXPECT_FALSE(robot_->model().moving());
  EXPECT_FALSE(robot_->model().connected());
  const auto received = Received();
  ASSERT_GE(received.size(), 3u);
  const size_t n = received.size();
  EXPECT_TRUE(Is(received[n - 3], cmd::kVel, true));
  EXPECT_EQ(received[n - 3].command.value, 0);
  EXPECT_TRUE(Is(received[n - 2], cmd::kRvel, true));
  EXPECT_EQ(received[n - 2].command.value, 0);
  EXPECT_TRUE(Is(received[n - 1], cmd::kClose, true));
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kStopped);
  EXPECT_EQ(sink_.status.back().state, "stopped");
  EXPECT_FALSE(sink_.status.back().connected);
}

// The process's loop (p3dx_main.cc) waits only for the driver's timers and the link: every
// timer must be announced by MillisecondsUntilDue() and the link's bytes must be read at once.
TEST_F(P3dxDriverTest, ProcessLoopKeepsAnIdleSessionWithAFewWakeupsASecond) {
  Start(P3dxRobotModelOptions{}, /*bytes_per_second=*/0.0);  // each packet arrives whole
  RunAsProcessFor(1.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  const size_t first = Received().size();
  const int64_t sips_before = robot_->model().sips_sent();
  const size_t odometry_before = sink_.odometry.size();
  const int64_t wakeups = RunAsProcessFor(10.0);
  RecordProperty("wakeups_in_10_s", static_cast<int>(wakeups));
  // 10 SIPs, 2 PULSEs and 1 BASE_STATUS a second (the robot's own SIP schedule adds up to 10
  // more here); a loop that polled the link every 10 ms would wake 1000 times.
  EXPECT_LE(wakeups, 10 * 23);
  EXPECT_GE(wakeups, 10 * 10);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  EXPECT_EQ(static_cast<int64_t>(sink_.odometry.size() - odometry_before),
            robot_->model().sips_sent() - sips_before);
  // Every SIP is published the moment it arrives.
  const auto received = Received();
  ASSERT_GT(received.size(), first + 15);
  int64_t previous = received[first - 1].time_us;
  for (size_t i = first; i < received.size(); ++i) {
    EXPECT_TRUE(Is(received[i], cmd::kPulse, true));
    EXPECT_LE(received[i].time_us - previous, 501000);  // pulse_interval_s + 1 ms rounding
    previous = received[i].time_us;
  }
  EXPECT_EQ(robot_->model().watchdog_stops(), 0);
}

TEST_F(P3dxDriverTest, ProcessLoopStopsTheRobotOnTimeWhenCommandsStop) {
  options_.command_timeout_s = 0.5;
  Start();
  RunAsProcessFor(1.0);
  RunAsProcessFor(1.0, CommandsAt10Hz(0.3, 0.0));
  ASSERT_TRUE(robot_->model().moving());
  const int64_t last_command = last_command_us_;
  int64_t stopped_at = -1;
  RunAsProcessFor(1.0, [&] {
    if (stopped_at < 0 && !robot_->model().moving()) stopped_at = clock_.now_us;
  });
  ASSERT_GE(stopped_at, 0);
  EXPECT_GE(stopped_at - last_command, 500000);
  EXPECT_LE(stopped_at - last_command, 501000);  // the timer, rounded up to a millisecond
  EXPECT_TRUE(driver_->Status().command_timeout_stop);
}

TEST_F(P3dxDriverTest, ProcessLoopReopensAnUnpluggedLinkOnItsBackoffAndNoSooner) {
  Start();
  RunAsProcessFor(1.0);
  ASSERT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  robot_->Unplug();
  std::vector<int64_t> attempts;
  int opens = robot_->opens();
  const int64_t wakeups = RunAsProcessFor(8.0, [&] {
    if (robot_->opens() != opens) {
      opens = robot_->opens();
      attempts.push_back(clock_.now_us);
    }
  });
  // The loss is seen at the next write or SIP timeout; then attempts 0.5, 1, 2, 4 s apart.
  ASSERT_GE(attempts.size(), 4u);
  const int64_t gaps[] = {1000000, 2000000, 4000000};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_GE(attempts[i + 1] - attempts[i], gaps[i]) << i;
    EXPECT_LE(attempts[i + 1] - attempts[i], gaps[i] + 1000) << i;
  }
  // Without a link the loop wakes for the attempts and the once-a-second status only.
  RecordProperty("wakeups_in_8_s_unplugged", static_cast<int>(wakeups));
  EXPECT_LE(wakeups, 30);
  robot_->Plug();
  RunAsProcessFor(10.0);
  EXPECT_EQ(driver_->state(), P3dxDriver::State::kRunning);
  EXPECT_EQ(driver_->Status().reconnects, 1);
}

TEST_F(P3dxDriverTest, NothingIsDueAfterShutdown) {
  Start();
  RunAsProcessFor(1.0);
  driver_->Shutdown();
  EXPECT_EQ(driver_->MillisecondsUntilDue(), 0);
  EXPECT_EQ(driver_->LinkPollDescriptor(), -1);
  const size_t published = sink_.status.size() + sink_.odometry.size();
  driver_->Poll(0);
  EXPECT_EQ(sink_.status.size() + sink_.odometry.size(), published);
}

TEST_F(P3dxDriverTest, SameRunTwiceGivesTheSameOdometry) {
  auto run = [] {
    DriverBench bench;
    bench.Start();
    bench.RunFor(1.0);
    bench.robot_->model().InjectGarbage(100);
    bench.robot_->model().CorruptNextChecksums(2);
    bench.RunFor(3.0, bench.CommandsAt10Hz(0.3, -0.4));
    return bench.sink_.odometry;
  };
  const auto first = run();
  const auto second = run();
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(Encode(first[i]), Encode(second[i])) << i;
  }
}

}  // namespace
}  // namespace slammtt
