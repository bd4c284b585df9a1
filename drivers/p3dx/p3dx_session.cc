#include "drivers/p3dx/p3dx_session.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/checked_options.h"
#include "common/report_count.h"
#include "drivers/p3dx/p3dx_commands.h"

namespace slammtt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int64_t kPartialPacketTimeoutUs = 100000;  // ARIA drops a packet after 100 ms of quiet
constexpr int64_t kStaleEstopAfterUs = 1000000;      // a stale robot still moving after VEL2 0
constexpr int64_t kStaleCloseQuietUs = 300000;       // no SIP for this long after CLOSE: closed
constexpr int64_t kStaleCloseGiveUpUs = 3000000;
constexpr int kWriteTimeoutMs = 500;
constexpr int kStopWriteTimeoutMs = 50;             // the stop when a link is given up
constexpr int64_t kShutdownDrainUs = 500000;         // read after CLOSE: see Shutdown()
constexpr int64_t kShutdownQuietUs = 150000;

int64_t Seconds(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

}  // namespace

P3dxSession::P3dxSession(const P3dxDriverOptions& options, ByteStreamFactory factory,
                         DriverClock* clock, P3dxSessionOutput* output, DriverLog* log)
    : options_(CheckedOptions(options, &CheckP3dxDriverOptions, "P3-DX driver options")),
      factory_(std::move(factory)),
      clock_(clock),
      output_(output),
      log_(log),
      endpoint_description_(options.port),
      backoff_(std::llround(options.reconnect_initial_s * 1000.0),
               std::llround(options.reconnect_max_s * 1000.0)) {
  next_attempt_us_ = clock_->NowMonotonicUs();
  next_status_us_ = next_attempt_us_;
}

P3dxSession::~P3dxSession() {
  if (state_ != State::kStopped) {
    try {
      Shutdown();
    } catch (...) {  // a destructor must not throw; Shutdown() already reports what it can
    }
  }
}

const char* P3dxSession::StateName(State state) {
  switch (state) {
    case State::kDisconnected: return "disconnected";
    case State::kSyncing: return "syncing";
    case State::kStoppingStale: return "stopping-earlier-session";
    case State::kClosingStale: return "closing-earlier-session";
    case State::kOpening: return "opening";
    case State::kRunning: return "running";
    case State::kStopped: return "stopped";
  }
  return "unknown";
}

void P3dxSession::SetState(State state) {
  if (state == state_) return;
  state_ = state;
  PublishStatus();
}

int P3dxSession::MillisecondsUntilDue() const {
  if (state_ == State::kStopped) return 0;
  const int64_t due_us = link_ ? NextTimerUs() : std::min(next_attempt_us_, next_status_us_);
  const int64_t wait_us = due_us - clock_->NowMonotonicUs();
  if (wait_us <= 0) return 0;
  return static_cast<int>(
      std::min<int64_t>((wait_us + 999) / 1000, std::numeric_limits<int>::max()));
}

void P3dxSession::Poll(int max_wait_ms) {
  if (state_ == State::kStopped) return;
  const int64_t now = clock_->NowMonotonicUs();
  try {
    if (!link_ && now >= next_attempt_us_) TryOpen(now);
    if (link_) RunTimers(now);
    if (link_) {
      const int64_t until_timer_us = NextTimerUs() - now;
      const int wait_ms = static_cast<int>(
          std::clamp<int64_t>((until_timer_us + 999) / 1000, 0, std::max(0, max_wait_ms)));
      ReadLink(wait_ms);
    }
  } catch (const LinkError& e) {
    LinkLost(e.what());
  }
  if (clock_->NowMonotonicUs() >= next_status_us_) PublishStatus();
}

void P3dxSession::TryOpen(int64_t now_us) {
  try {
    link_ = factory_(options_.port, options_.baud);
  } catch (const std::exception& e) {
    link_.reset();
    last_error_ = e.what();
    const int64_t delay_ms = backoff_.NextDelayMs();
    next_attempt_us_ = now_us + delay_ms * 1000;
    LogWarning() << e.what() << "; next attempt in " << delay_ms / 1000.0 << " s";
    PublishStatus();
    return;
  }
  endpoint_description_ = link_->Describe();
  decoder_.Reset();
  link_->FlushInput();
  LogInfo() << "opened " << endpoint_description_ << ", synchronising";
  StartSync();
}

void P3dxSession::LinkLost(const std::string& reason) {
  if (!link_) return;
  // A link given up for silence may still carry our bytes to a robot that drives on: stop it
  // before letting go (a write that fails here changes nothing).
  try {
    const std::vector<uint8_t> stop = EncodeP3dxVel2(0, 0);
    link_->Write(stop.data(), stop.size(), kStopWriteTimeoutMs);
  } catch (const LinkError&) {
  }
  link_.reset();
  if (shutting_down_) {
    LogWarning() << endpoint_description_ << ": link lost while stopping (" << reason << ")";
    return;
  }
  decoder_.Reset();
  odometry_.Reanchor();
  sent_once_ = false;
  last_error_ = reason;
  const int64_t delay_ms = backoff_.NextDelayMs();
  next_attempt_us_ = clock_->NowMonotonicUs() + delay_ms * 1000;
  LogWarning() << endpoint_description_ << ": link lost (" << reason << "); reconnecting in "
               << delay_ms / 1000.0 << " s";
  SetState(State::kDisconnected);
}

bool P3dxSession::Send(const std::vector<uint8_t>& packet) {
  if (!link_) return false;
  try {
    link_->Write(packet.data(), packet.size(), kWriteTimeoutMs);
  } catch (const LinkError& e) {
    LinkLost(e.what());
    return false;
  }
  last_write_us_ = clock_->NowMonotonicUs();
  return true;
}

void P3dxSession::StartSync() {
  SetState(State::kSyncing);
  sync_attempts_ = 0;
  SendSync(0);
}

void P3dxSession::SendSync(int index) {
  sync_index_ = index;
  ++sync_attempts_;
  sync_sent_us_ = clock_->NowMonotonicUs();
  // A robot still in an earlier session takes SYNC0 as a keep-alive and keeps its last speed:
  // every SYNC0 goes out behind a stop. A robot waiting for SYNC0 ignores it.
  if (index == 0 && !Send(EncodeP3dxVel2(0, 0))) return;
  Send(EncodeP3dxCommand(static_cast<uint8_t>(index)));
}

int64_t P3dxSession::NextTimerUs() const {
  int64_t next = next_status_us_;
  switch (state_) {
    case State::kSyncing:
      next = std::min(next, sync_sent_us_ + Seconds(options_.sync_reply_timeout_s));
      break;
    case State::kStoppingStale:
      next = std::min(next, last_stale_sip_us_ + Seconds(options_.sip_timeout_s));
      break;
    case State::kClosingStale:
      next = std::min(next, std::max(last_stale_sip_us_, close_sent_us_) + kStaleCloseQuietUs);
      break;
    case State::kOpening:
      next = std::min(next, opened_us_ + Seconds(options_.sip_timeout_s));
      break;
    case State::kRunning:
      next = std::min(next, last_sip_us_ + Seconds(options_.sip_timeout_s));
      next = std::min(next, last_write_us_ + Seconds(options_.pulse_interval_s));
      if (have_command_) {
        next = std::min(next, last_command_us_ + Seconds(options_.command_timeout_s));
      }
      break;
    case State::kDisconnected:
    case State::kStopped:
      break;
  }
  if (decoder_.HasPartial()) next = std::min(next, last_byte_us_ + kPartialPacketTimeoutUs);
  return next;
}

void P3dxSession::RunTimers(int64_t now) {
  switch (state_) {
    case State::kSyncing:
      if (now - sync_sent_us_ >= Seconds(options_.sync_reply_timeout_s)) {
        if (sync_attempts_ >= options_.sync_attempts) {
          LinkLost("no reply to SYNC" + std::to_string(sync_index_) + " after " +
                   std::to_string(sync_attempts_) + " attempts");
          return;
        }
        SendSync(sync_index_);
      }
      break;
    case State::kStoppingStale:
      if (now - last_stale_sip_us_ >= Seconds(options_.sip_timeout_s)) StartSync();
      break;
    case State::kClosingStale:
      if (now - close_sent_us_ >= kStaleCloseGiveUpUs) {
        LinkLost("the earlier session did not close");
        return;
      }
      if (now - std::max(last_stale_sip_us_, close_sent_us_) >= kStaleCloseQuietUs) {
        decoder_.Reset();
        link_->FlushInput();
        LogInfo() << "earlier session closed; synchronising again";
        StartSync();
      }
      break;
    case State::kOpening:
      if (now - opened_us_ >= Seconds(options_.sip_timeout_s)) {
        LinkLost("no SIP after OPEN");
        return;
      }
      break;
    case State::kRunning:
      if (now - last_sip_us_ >= Seconds(options_.sip_timeout_s)) {
        std::ostringstream reason;
        reason << "no valid SIP for " << options_.sip_timeout_s << " s";
        LinkLost(reason.str());
        return;
      }
      if (have_command_ && now - last_command_us_ >= Seconds(options_.command_timeout_s)) {
        have_command_ = false;
        if (target_vel_mmps_ != 0 || target_rvel_degps_ != 0 || sent_vel_mmps_ != 0 ||
            sent_rvel_degps_ != 0) {
          target_vel_mmps_ = 0;
          target_rvel_degps_ = 0;
          command_timeout_stop_ = true;
          LogWarning() << "no VELOCITY_COMMAND for " << options_.command_timeout_s
                       << " s: stopping the robot";
          SendVelocity();
          PublishStatus();
          return;
        }
      }
      if (now - last_write_us_ >= Seconds(options_.pulse_interval_s)) {
        if (sent_vel_mmps_ != 0 || sent_rvel_degps_ != 0) {
          SendVelocity();  // repeating it also repairs a VEL lost on the line
        } else {
          Send(EncodeP3dxCommand(p3dx_command::kPulse));
        }
      }
      break;
    case State::kDisconnected:
    case State::kStopped:
      break;
  }
}

void P3dxSession::ReadLink(int wait_ms) {
  uint8_t buffer[512];
  const size_t n = link_->Read(buffer, sizeof buffer, wait_ms);
  const int64_t now = clock_->NowMonotonicUs();
  if (n > 0) {
    last_byte_us_ = now;
    decoder_.Feed(buffer, n);
  } else if (decoder_.HasPartial() && now - last_byte_us_ >= kPartialPacketTimeoutUs) {
    decoder_.DiscardPartial();
  } else {
    return;
  }
  // The host time at which the packets' last bytes were read: the SIP's arrival.
  const int64_t arrival_utime = clock_->NowUtime();
  while (link_) {
    auto payload = decoder_.Next();
    if (!payload) break;
    HandlePacket(*payload, arrival_utime);
  }
}

void P3dxSession::HandlePacket(const std::vector<uint8_t>& payload, int64_t arrival_utime) {
  switch (state_) {
    case State::kSyncing:
      HandleSyncReply(payload);
      return;
    case State::kStoppingStale:
    case State::kClosingStale: {
      const P3dxSipParse parse = ParseP3dxStandardSip(payload);
      if (parse.status == P3dxSipStatus::kOk) HandleStaleSip(parse.sip);
      if (parse.status == P3dxSipStatus::kShort) ++short_sips_;
      return;
    }
    case State::kOpening:
    case State::kRunning: {
      const P3dxSipParse parse = ParseP3dxStandardSip(payload);
      if (parse.status == P3dxSipStatus::kOk) {
        HandleSip(parse.sip, arrival_utime);
      } else if (parse.status == P3dxSipStatus::kShort) {
        ++short_sips_;
      } else {
        ++other_packets_;  // late sync replies, configuration packets: not ours to use
      }
      return;
    }
    case State::kDisconnected:
    case State::kStopped:
      return;
  }
}

void P3dxSession::HandleSyncReply(const std::vector<uint8_t>& payload) {
  const uint8_t id = payload[0];
  if (IsP3dxSipType(id)) {
    const P3dxSipParse parse = ParseP3dxStandardSip(payload);
    if (parse.status != P3dxSipStatus::kOk) {
      ++short_sips_;
      return;
    }
    const int64_t now = clock_->NowMonotonicUs();
    last_stale_sip_us_ = now;
    if (parse.sip.moving) {
      LogWarning() << "the robot is still in an earlier session and moving: stopping it";
      stale_since_us_ = now;
      stale_estop_sent_ = false;
      if (!Send(EncodeP3dxVel2(0, 0))) return;
      SetState(State::kStoppingStale);
    } else {
      LogWarning() << "the robot is still in an earlier session: closing it";
      close_sent_us_ = now;
      if (!Send(EncodeP3dxCommand(p3dx_command::kClose))) return;
      SetState(State::kClosingStale);
    }
    return;
  }
  if (id < sync_index_ && payload.size() == 1) return;  // a late duplicate echo
  if (id != sync_index_ || (id < 2 && payload.size() != 1)) {
    LogDebug() << "unexpected reply 0x" << std::hex << static_cast<int>(id) << " to SYNC"
               << sync_index_ << "; starting over";
    sync_attempts_ = 0;
    SendSync(0);
    return;
  }
  if (sync_index_ < 2) {
    sync_attempts_ = 0;
    SendSync(sync_index_ + 1);
    return;
  }
  identity_ = ParseP3dxRobotIdentity(payload).value_or(P3dxRobotIdentity{});
  const std::string subclass = options_.subclass.empty() ? identity_.subclass : options_.subclass;
  std::optional<P3dxConversion> conversion = P3dxConversionForSubclass(subclass);
  if (!conversion) {
    conversion = P3dxConversion{};
    conversion->dist_conv_mm = 1.0;  // ARIA's default parameters
    LogWarning() << "no conversion factors for subclass '" << subclass
                 << "': using DistConvFactor 1.0 (set p3dx.subclass to force one)";
  }
  odometry_.SetConversion(*conversion);
  if (!Send(EncodeP3dxCommand(p3dx_command::kOpen))) return;
  if (options_.enable_motors && !Send(EncodeP3dxIntCommand(p3dx_command::kEnable, 1))) return;
  opened_us_ = clock_->NowMonotonicUs();
  // A new session starts with the robot at rest.
  sent_once_ = false;
  sent_vel_mmps_ = 0;
  sent_rvel_degps_ = 0;
  SetState(State::kOpening);
}

void P3dxSession::HandleStaleSip(const P3dxStandardSip& sip) {
  const int64_t now = clock_->NowMonotonicUs();
  last_stale_sip_us_ = now;
  if (state_ == State::kStoppingStale) {
    if (!sip.moving) {
      close_sent_us_ = now;
      if (!Send(EncodeP3dxCommand(p3dx_command::kClose))) return;
      SetState(State::kClosingStale);
    } else if (!stale_estop_sent_ && now - stale_since_us_ >= kStaleEstopAfterUs) {
      LogWarning() << "the robot still moves 1 s after VEL2 0: ESTOP";
      stale_estop_sent_ = true;
      Send(EncodeP3dxCommand(p3dx_command::kEstop));
    } else {
      Send(EncodeP3dxVel2(0, 0));
    }
    return;
  }
  // kClosingStale: SIPs already on the way when CLOSE left are expected; repeat CLOSE if they
  // go on.
  if (now - close_sent_us_ >= kStaleCloseQuietUs) {
    close_sent_us_ = now;
    Send(EncodeP3dxCommand(p3dx_command::kClose));
  }
}

void P3dxSession::HandleSip(const P3dxStandardSip& sip, int64_t arrival_utime) {
  const int64_t now = clock_->NowMonotonicUs();
  last_sip_us_ = now;
  if (state_ == State::kOpening) {
    if (had_session_) ++reconnects_;
    had_session_ = true;
    backoff_.Reset();
    LogInfo() << "connected to '" << identity_.name << "' (" << identity_.robot_class << " "
              << identity_.subclass << ") on " << endpoint_description_;
    SetState(State::kRunning);
    // Only a command that is still fresh moves the new session; a stale one would drive the
    // robot until the command timeout caught it.
    if (have_command_ && now - last_command_us_ < Seconds(options_.command_timeout_s)) {
      SendVelocity();
      if (!link_) return;
    }
  }
  const bool flags_changed =
      !have_sip_ || sip.stall_and_bumpers != last_sip_.stall_and_bumpers ||
      sip.motors_enabled() != last_sip_.motors_enabled();
  last_sip_ = sip;
  have_sip_ = true;
  ++sips_received_;

  BaseOdometry odometry;
  odometry.utime = arrival_utime;
  odometry.sequence = odometry_sequence_++;
  odometry.reading = odometry_.Update(sip);
  output_->OnBaseOdometry(odometry);
  if (flags_changed) PublishStatus();
}

void P3dxSession::AcceptCommand(const BaseCommand& command) {
  if (state_ == State::kStopped) return;
  ++commands_accepted_;
  HandleCommand(command);
}

void P3dxSession::RefuseCommand(CommandRefusal reason, const std::string& why) {
  if (state_ == State::kStopped) return;
  ++(reason == CommandRefusal::kStale      ? commands_stale_
     : reason == CommandRefusal::kReplayed ? commands_replayed_
                                           : commands_unauthenticated_);
  if (IsReportable(commands_refused())) {
    LogWarning() << "VELOCITY_COMMAND refused: " << why << " (" << commands_refused()
                 << " refused so far, counted in BASE_STATUS)";
  }
}

void P3dxSession::HandleCommand(const BaseCommand& command) {
  if (state_ == State::kStopped) return;
  if (!std::isfinite(command.linear_mps) || !std::isfinite(command.angular_radps)) {
    ++commands_skipped_;
    last_error_ = "VELOCITY_COMMAND with a non-finite value skipped";
    if (IsReportable(commands_skipped_)) {
      LogWarning() << last_error_ << " (" << commands_skipped_ << " so far)";
    }
    return;
  }
  const double linear =
      std::clamp(command.linear_mps, -options_.max_linear_mps, options_.max_linear_mps);
  const double angular =
      std::clamp(command.angular_radps, -options_.max_angular_radps, options_.max_angular_radps);
  target_vel_mmps_ = static_cast<int>(std::lround(linear * 1000.0));
  target_rvel_degps_ = static_cast<int>(std::lround(angular * 180.0 / kPi));
  have_command_ = true;
  last_command_us_ = clock_->NowMonotonicUs();
  if (command_timeout_stop_) {
    command_timeout_stop_ = false;
    LogInfo() << "VELOCITY_COMMAND resumed";
    PublishStatus();
  }
  if (state_ == State::kRunning &&
      (!sent_once_ || target_vel_mmps_ != sent_vel_mmps_ ||
       target_rvel_degps_ != sent_rvel_degps_)) {
    SendVelocity();
  }
}

void P3dxSession::SendVelocity() {
  if (!Send(EncodeP3dxIntCommand(p3dx_command::kVel, target_vel_mmps_))) return;
  if (!Send(EncodeP3dxIntCommand(p3dx_command::kRvel, target_rvel_degps_))) return;
  sent_vel_mmps_ = target_vel_mmps_;
  sent_rvel_degps_ = target_rvel_degps_;
  sent_once_ = true;
}

void P3dxSession::Shutdown() {
  if (state_ == State::kStopped) return;
  shutting_down_ = true;
  if (link_) {
    // Stop first, then end the session; CLOSE alone also stops the robot, the explicit stop
    // makes sure of it should CLOSE be lost.
    const bool sent = Send(EncodeP3dxIntCommand(p3dx_command::kVel, 0)) &&
                      Send(EncodeP3dxIntCommand(p3dx_command::kRvel, 0)) &&
                      Send(EncodeP3dxCommand(p3dx_command::kClose));
    // Read until the robot's SIPs stop before closing the link: a TCP socket closed with unread
    // input resets the connection and can discard what we just wrote.
    const int64_t start = clock_->NowMonotonicUs();
    int64_t last_data = start;
    try {
      uint8_t buffer[256];
      while (sent && link_) {
        const int64_t now = clock_->NowMonotonicUs();
        if (now - start >= kShutdownDrainUs || now - last_data >= kShutdownQuietUs) break;
        if (link_->Read(buffer, sizeof buffer, 20) > 0) last_data = clock_->NowMonotonicUs();
      }
    } catch (const LinkError&) {  // the robot side went away first: nothing left to stop
    }
    if (sent) LogInfo() << "robot stopped and session closed (VEL 0, RVEL 0, CLOSE)";
    link_.reset();
  }
  state_ = State::kStopped;
  const BaseStatus status = Status();
  LogInfo() << "SIPs " << status.sips_received << ", checksum errors " << status.checksum_errors
            << ", short packets " << status.short_packets << ", bad byte counts "
            << decoder_.counters().bad_byte_counts << ", reconnects " << status.reconnects
            << ", commands accepted " << commands_accepted_ << ", refused " << commands_refused()
            << ", skipped " << commands_skipped_;
  PublishStatus();
}

BaseStatus P3dxSession::Status() const {
  BaseStatus status;
  status.utime = clock_->NowUtime();
  status.connected = state_ == State::kRunning;
  switch (state_) {
    case State::kDisconnected:
      status.state = had_session_ ? BaseState::kReconnecting : BaseState::kConnecting;
      break;
    case State::kSyncing: status.state = BaseState::kSyncing; break;
    case State::kStoppingStale: status.state = BaseState::kStoppingEarlierSession; break;
    case State::kClosingStale: status.state = BaseState::kClosingEarlierSession; break;
    case State::kOpening: status.state = BaseState::kOpening; break;
    case State::kRunning: status.state = BaseState::kRunning; break;
    case State::kStopped: status.state = BaseState::kStopped; break;
  }
  status.endpoint = endpoint_description_;
  status.robot_name = identity_.name;
  status.robot_class = identity_.robot_class;
  status.robot_subclass = identity_.subclass;
  if (have_sip_) {
    status.battery_v = last_sip_.battery_v();
    status.left_wheel_stall = last_sip_.left_wheel_stalled();
    status.right_wheel_stall = last_sip_.right_wheel_stalled();
    status.bumpers = last_sip_.bumpers();
    status.motors_enabled = last_sip_.motors_enabled();
  }
  status.command_timeout_stop = command_timeout_stop_;
  status.sips_received = sips_received_;
  status.checksum_errors = decoder_.counters().checksum_errors;
  status.short_packets = decoder_.counters().truncated + short_sips_;
  status.reconnects = reconnects_;
  status.last_error = last_error_;
  if (options_.command_authentication == P3dxDriverOptions::CommandAuthentication::kNone) {
    status.command_auth = CommandAuthState::kNone;
  } else {
    status.command_auth =
        command_key_loaded_ ? CommandAuthState::kSigned : CommandAuthState::kSignedWithoutKey;
  }
  status.commands_accepted = commands_accepted_;
  status.commands_unauthenticated = commands_unauthenticated_;
  status.commands_stale = commands_stale_;
  status.commands_replayed = commands_replayed_;
  return status;
}

void P3dxSession::PublishStatus() {
  next_status_us_ = clock_->NowMonotonicUs() + Seconds(options_.status_period_s);
  output_->OnBaseStatus(Status());
}

}  // namespace slammtt
