// slammtt-teleop: drives the base from a terminal's keyboard or from a scripted velocity
// profile, with signed VELOCITY_COMMAND (velocity_sender.h, as slammtt-drive) repeated at
// --rate-hz so that the base driver's command timeout never stops the robot while it is
// driven. Every way out sends a stop command and, in keyboard mode, gives the terminal its
// settings back. docs/robot.md, "Driving the robot".
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/velocity_sender.h"
#include "drivers/common/driver_clock.h"
#include "drivers/teleop/teleop_keys.h"
#include "drivers/teleop/velocity_profile.h"
#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

namespace slammtt {
namespace {

// The terminal on stdin in raw mode (no line buffering, no echo; Ctrl-C still a signal) for as
// long as this object lives: the destructor restores the settings on every way out, an
// exception included.
class RawTerminal {
 public:
  RawTerminal() {
    if (!isatty(STDIN_FILENO)) {
      throw UsageError("keyboard mode needs a terminal on stdin (or --profile FILE)");
    }
    if (tcgetattr(STDIN_FILENO, &saved_) != 0) {
      throw std::runtime_error("cannot read the terminal's settings");
    }
    termios raw = saved_;
    raw.c_lflag &= static_cast<tcflag_t>(~(ICANON | ECHO));
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    if (tcsetattr(STDIN_FILENO, TCSANOW, &raw) != 0) {
      throw std::runtime_error("cannot put the terminal into raw mode");
    }
  }
  ~RawTerminal() {
    tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
    std::fputs("\n", stderr);
  }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;

 private:
  termios saved_{};
};

// Sends a stop when it goes, however the program ends (a failing bus is reported, not thrown
// from a destructor).
class StopOnExit {
 public:
  explicit StopOnExit(SignedVelocitySender* sender) : sender_(sender) {}
  ~StopOnExit() {
    try {
      sender_->Send(0.0, 0.0);
      LogInfo() << "robot stopped; sent " << sender_->sent() << " signed commands on "
                << sender_->channel();
    } catch (const std::exception& e) {
      LogError() << "could not send the stop command: " << e.what();
    }
  }
  StopOnExit(const StopOnExit&) = delete;
  StopOnExit& operator=(const StopOnExit&) = delete;

 private:
  SignedVelocitySender* sender_;
};

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the profile");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Sends the profile's command of the moment now and every period until it ends, paced by the
// process's loop.
void RunProfile(const std::vector<VelocityProfileStep>& steps, SignedVelocitySender* sender,
                EventLoop* loop, int64_t period_us) {
  const int64_t start_us = loop->clock().NowUs();
  int last_line = 0;
  bool done = false;
  const auto send_due = [&] {
    const double elapsed_s = static_cast<double>(loop->clock().NowUs() - start_us) * 1e-6;
    const std::optional<VelocityProfileStep> step = ProfileStepAt(steps, elapsed_s);
    if (!step) {
      done = true;
      return;
    }
    if (step->line != last_line) {
      LogInfo() << "line " << step->line << ": " << step->linear_mps << " m/s, "
                << step->angular_radps << " rad/s for " << step->duration_s << " s";
      last_line = step->line;
    }
    sender->Send(step->linear_mps, step->angular_radps);
  };
  send_due();
  loop->AddTimer(period_us, send_due);
  while (!done && !ShutdownRequested()) loop->HandleTimeoutUs(period_us);
}

// The keyboard on stdin through the loop's descriptor hook; the command of the moment goes out
// at once when a key changes it and every period from the loop's timer.
void RunKeyboard(const TeleopSteps& steps, SignedVelocitySender* sender, EventLoop* loop,
                 int64_t period_us) {
  RawTerminal terminal;
  std::fputs("slammtt-teleop: arrows or w a s d change speed and turn, space stops, q quits\n",
             stderr);
  TerminalKeyDecoder decoder;
  TeleopCommand command;
  bool quit = false;
  loop->AddFdHook(STDIN_FILENO, [&] {
    uint8_t bytes[64];
    const ssize_t got = read(STDIN_FILENO, bytes, sizeof bytes);
    if (got == 0 || (got < 0 && errno != EAGAIN && errno != EINTR)) {  // the terminal went away
      quit = true;
      return;
    }
    const TeleopCommand before = command;
    for (TeleopKey key : decoder.Feed(bytes, got > 0 ? static_cast<size_t>(got) : 0)) {
      if (key == TeleopKey::kQuit) quit = true;
      command = ApplyTeleopKey(command, key, steps);
    }
    if (!quit && (command.linear_mps != before.linear_mps ||
                  command.angular_radps != before.angular_radps)) {
      std::fprintf(stderr, "\rlinear %+.2f m/s  angular %+.2f rad/s   ", command.linear_mps,
                   command.angular_radps);
      sender->Send(command.linear_mps, command.angular_radps);  // a change goes out at once
    }
  });
  const auto send = [&] { sender->Send(command.linear_mps, command.angular_radps); };
  send();
  loop->AddTimer(period_us, send);
  while (!quit && !ShutdownRequested()) loop->HandleTimeoutUs(period_us);
}

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-teleop", "--key FILE [--profile FILE] [options]",
                 "Drives the base with signed VELOCITY_COMMAND at --rate-hz: from the keyboard "
                 "(arrows or w a s d, space stops, q quits) or, with --profile, from a file of "
                 "lines 'duration_s linear_mps angular_radps' (# comments). Sends a stop on "
                 "every way out. The key is the robot's (p3dx.command_key_file).");
  AddStandardOptions(&cl);
  cl.AddOption("key", "FILE", "the command key shared with the robot (required)");
  cl.AddOption("profile", "FILE", "drive this velocity profile instead of the keyboard");
  AddCommandRateOption(&cl);
  cl.AddOption("linear-step-mps", "V", "keyboard: speed change per key press (default 0.05)");
  cl.AddOption("angular-step-radps", "W", "keyboard: turn rate change per key (default 0.1)");
  cl.AddOption("max-linear-mps", "V", "keyboard: speed limit (default 0.5)");
  cl.AddOption("max-angular-radps", "W", "keyboard: turn rate limit (default 1)");
  if (!cl.Parse(argc, argv)) return 0;
  const ProcessSettings settings = LoadProcessSettings(cl);
  const auto key_path = cl.Value("key");
  if (!key_path) throw UsageError("--key FILE is required");
  const int64_t period_us = CommandPeriodUs(cl);
  TeleopSteps steps;
  const auto positive = [&cl](const char* name, double fallback, double limit) {
    const double value = cl.DoubleValue(name).value_or(fallback);
    if (!(value > 0.0 && value <= limit)) {
      throw UsageError(std::string("--") + name + " must be in (0, " + std::to_string(limit) +
                       "]");
    }
    return value;
  };
  steps.linear_step_mps = positive("linear-step-mps", steps.linear_step_mps, 1.0);
  steps.angular_step_radps = positive("angular-step-radps", steps.angular_step_radps, 2.0);
  steps.max_linear_mps = positive("max-linear-mps", steps.max_linear_mps, kMaxProfileLinearMps);
  steps.max_angular_radps =
      positive("max-angular-radps", steps.max_angular_radps, kMaxProfileAngularRadps);
  // The whole profile is read and checked before anything is sent.
  std::vector<VelocityProfileStep> profile;
  if (auto path = cl.Value("profile")) profile = ParseVelocityProfile(ReadTextFile(*path), *path);
  if (profile.empty() && !isatty(STDIN_FILENO)) {
    throw UsageError("keyboard mode needs a terminal on stdin (or --profile FILE)");
  }

  const CommandKey key = LoadCommandKeyFile(*key_path);
  LcmBus bus(settings.lcm_url);
  SystemDriverClock clock;
  SignedVelocitySender sender(key, settings.channels.Get("velocity_command"), &bus, &clock);
  StopOnExit stop(&sender);
  SteadyMonotonicClock loop_clock;
  EventLoop loop(&bus, &loop_clock);
  if (!profile.empty()) {
    LogInfo() << "profile of " << profile.size() << " steps, " << ProfileDurationS(profile)
              << " s";
    RunProfile(profile, &sender, &loop, period_us);
  } else {
    RunKeyboard(steps, &sender, &loop, period_us);
  }
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-teleop", slammtt::Run);
}
