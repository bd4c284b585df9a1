// The device session alone: plain commands in, plain odometry and status out, its log lines to a
// recording log; no message and no bus (the whole lifecycle is p3dx_driver_test, through the
// program's adapter).
#include "drivers/p3dx/p3dx_session.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "simulated_robot_link.h"

namespace slammtt {
namespace {

struct RecordingOutput : P3dxSessionOutput {
  void OnBaseOdometry(const BaseOdometry& odometry) override { odometry_.push_back(odometry); }
  void OnBaseStatus(const BaseStatus& status) override { statuses.push_back(status); }
  std::vector<BaseOdometry> odometry_;
  std::vector<BaseStatus> statuses;
};

struct RecordingLog : DriverLog {
  void Write(DriverLogLevel level, const std::string& line) override {
    lines.emplace_back(level, line);
  }
  int Count(DriverLogLevel level, const std::string& text) const {
    int count = 0;
    for (const auto& [l, line] : lines) count += l == level && line.find(text) != std::string::npos;
    return count;
  }
  std::vector<std::pair<DriverLogLevel, std::string>> lines;
};

class P3dxSessionTest : public ::testing::Test {
 protected:
  void Start() {
    robot_ = std::make_unique<SimulatedRobot>(P3dxRobotModelOptions{}, &clock_);
    options_.port = "/dev/ttyUSB0";
    session_ = std::make_unique<P3dxSession>(
        options_,
        [this](const std::string& endpoint, int baud) { return robot_->Open(endpoint, baud); },
        &clock_, &output_, &log_);
  }
  void RunFor(double seconds) {
    const int64_t end = clock_.now_us + static_cast<int64_t>(seconds * 1e6);
    while (clock_.now_us < end) {
      const int64_t before = clock_.now_us;
      session_->Poll(10);
      if (clock_.now_us == before) clock_.now_us += 1000;
      robot_->Sync();
    }
  }
  double SpeedMmps() const {
    return 0.5 * (robot_->model().left_wheel_mmps() + robot_->model().right_wheel_mmps());
  }

  SimulatedClock clock_;
  std::unique_ptr<SimulatedRobot> robot_;
  RecordingOutput output_;
  RecordingLog log_;
  P3dxDriverOptions options_;
  std::unique_ptr<P3dxSession> session_;
};

TEST_F(P3dxSessionTest, ConnectsAndReportsOdometryAndStatusAsPlainStructs) {
  Start();
  RunFor(2.0);
  ASSERT_EQ(session_->state(), P3dxSession::State::kRunning);
  ASSERT_GE(output_.odometry_.size(), 10u);
  for (size_t i = 0; i < output_.odometry_.size(); ++i) {
    EXPECT_EQ(output_.odometry_[i].sequence, static_cast<int64_t>(i));
    EXPECT_GT(output_.odometry_[i].utime, SimulatedClock::kEpochOffsetUs);
  }
  ASSERT_FALSE(output_.statuses.empty());
  EXPECT_EQ(output_.statuses.front().state, BaseState::kSyncing);  // the link opened at once
  const BaseStatus status = session_->Status();
  EXPECT_EQ(status.state, BaseState::kRunning);
  EXPECT_TRUE(status.connected);
  EXPECT_EQ(status.robot_subclass, "p3dx");
  EXPECT_TRUE(status.motors_enabled);
  EXPECT_GT(status.battery_v, 10.0);
  EXPECT_EQ(status.command_auth, CommandAuthState::kSignedWithoutKey);
  EXPECT_EQ(status.utime, clock_.NowUtime());
  EXPECT_EQ(log_.Count(DriverLogLevel::kInfo, "opened "), 1);
  EXPECT_EQ(log_.Count(DriverLogLevel::kInfo, "connected to 'slammtt-emulator' (Pioneer p3dx)"),
            1);

  session_->Shutdown();
  EXPECT_EQ(output_.statuses.back().state, BaseState::kStopped);
  EXPECT_EQ(log_.Count(DriverLogLevel::kInfo, "robot stopped and session closed"), 1);
}

TEST_F(P3dxSessionTest, AcceptedCommandsDriveRefusedOnesAreCountedAndReported) {
  Start();
  session_->SetCommandKeyLoaded();
  RunFor(1.0);
  BaseCommand forward;
  forward.linear_mps = 0.3;
  for (int k = 0; k < 10; ++k) {
    session_->RefuseCommand(CommandRefusal::kUnauthenticated, "unauthenticated (test)");
  }
  session_->RefuseCommand(CommandRefusal::kStale, "stale (test)");
  session_->RefuseCommand(CommandRefusal::kReplayed, "replayed (test)");
  RunFor(0.1);
  EXPECT_EQ(SpeedMmps(), 0.0) << "a refused command never moves the robot";
  session_->AcceptCommand(forward);
  RunFor(0.05);
  EXPECT_NEAR(SpeedMmps(), 300.0, 1e-9);

  const BaseStatus status = session_->Status();
  EXPECT_EQ(status.command_auth, CommandAuthState::kSigned);
  EXPECT_EQ(status.commands_accepted, 1);
  EXPECT_EQ(status.commands_unauthenticated, 10);
  EXPECT_EQ(status.commands_stale, 1);
  EXPECT_EQ(status.commands_replayed, 1);
  EXPECT_EQ(session_->commands_refused(), 12);
  // The 1st and the 10th refusal are reported, with the reason the adapter gave.
  EXPECT_EQ(log_.Count(DriverLogLevel::kWarning, "VELOCITY_COMMAND refused: "), 2);
  EXPECT_EQ(log_.Count(DriverLogLevel::kWarning,
                       "VELOCITY_COMMAND refused: unauthenticated (test) (10 refused so far, "
                       "counted in BASE_STATUS)"),
            1);

  session_->Shutdown();
  session_->AcceptCommand(forward);
  session_->RefuseCommand(CommandRefusal::kStale, "stale (test)");
  EXPECT_EQ(session_->Status().commands_accepted, 1) << "nothing after Shutdown()";
  EXPECT_EQ(session_->Status().commands_stale, 1);
}

TEST_F(P3dxSessionTest, ANonFiniteCommandIsSkippedAndCounted) {
  Start();
  RunFor(1.0);
  BaseCommand bad;
  bad.linear_mps = std::numeric_limits<double>::quiet_NaN();
  session_->HandleCommand(bad);
  EXPECT_EQ(session_->commands_skipped(), 1);
  EXPECT_EQ(session_->Status().last_error, "VELOCITY_COMMAND with a non-finite value skipped");
  EXPECT_EQ(log_.Count(DriverLogLevel::kWarning, "non-finite value skipped (1 so far)"), 1);
}

}  // namespace
}  // namespace slammtt
