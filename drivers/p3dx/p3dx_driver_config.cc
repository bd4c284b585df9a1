#include "drivers/p3dx/p3dx_driver_config.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/p3dx/p3dx_odometry.h"
#include "runtime/lcm_url.h"

namespace slammtt {
namespace {

// An integer key in [minimum, maximum], checked before it is narrowed to int (a baud rate of
// 2^32 + 9600 must be an error, not 9600).
int ReadBoundedInt(const Config& section, const std::string& key, int fallback, int64_t minimum,
                   int64_t maximum) {
  const int64_t value = section.GetInt(key, fallback);
  if (value < minimum || value > maximum) {
    section.FailKey(key, "must be an integer from " + std::to_string(minimum) + " to " +
                             std::to_string(maximum) + ", got " + std::to_string(value));
  }
  return static_cast<int>(value);
}

constexpr int64_t kMaxBaud = 10000000;

}  // namespace

P3dxDriverOptions ReadP3dxDriverOptions(const Config& section) {
  P3dxDriverOptions o;
  o.port = section.GetString("port", o.port);
  o.baud = ReadBoundedInt(section, "baud", o.baud, 1, kMaxBaud);
  o.max_linear_mps = section.GetDouble("max_linear_mps", o.max_linear_mps);
  o.max_angular_radps = section.GetDouble("max_angular_radps", o.max_angular_radps);
  o.command_timeout_s = section.GetDouble("command_timeout_s", o.command_timeout_s);
  o.pulse_interval_s = section.GetDouble("pulse_interval_s", o.pulse_interval_s);
  o.sync_reply_timeout_s = section.GetDouble("sync_reply_timeout_s", o.sync_reply_timeout_s);
  o.sync_attempts = ReadBoundedInt(section, "sync_attempts", o.sync_attempts, 1, 1000);
  o.sip_timeout_s = section.GetDouble("sip_timeout_s", o.sip_timeout_s);
  o.reconnect_initial_s = section.GetDouble("reconnect_initial_s", o.reconnect_initial_s);
  o.reconnect_max_s = section.GetDouble("reconnect_max_s", o.reconnect_max_s);
  o.subclass = section.GetString("subclass", o.subclass);
  o.enable_motors = section.GetBool("enable_motors", o.enable_motors);
  o.status_period_s = section.GetDouble("status_period_s", o.status_period_s);
  const std::string auth = section.GetString(
      "command_authentication", CommandAuthenticationName(o.command_authentication));
  if (auth == "hmac-sha256") {
    o.command_authentication = P3dxDriverOptions::CommandAuthentication::kSigned;
  } else if (auth == "none") {
    o.command_authentication = P3dxDriverOptions::CommandAuthentication::kNone;
  } else {
    section.FailKey("command_authentication",
                    "must be hmac-sha256 or none, got '" + auth + "'");
  }
  o.command_key_file = section.GetString("command_key_file", o.command_key_file);
  o.command_max_age_s = section.GetDouble("command_max_age_s", o.command_max_age_s);
  try {
    ValidateP3dxDriverOptions(o);
  } catch (const std::invalid_argument& e) {
    section.Fail(e.what());
  }
  return o;
}

void AddP3dxDriverOptions(CommandLine* command_line) {
  command_line->AddOption("port", "PORT",
                          "serial port or tcp://HOST:PORT of the robot (default p3dx.port, "
                          "/dev/ttyUSB0)");
  command_line->AddOption("baud", "RATE", "serial baud rate (default p3dx.baud, 9600)");
  command_line->AddOption("max-linear-mps", "V", "speed limit (default p3dx.max_linear_mps, 0.5)");
  command_line->AddOption("max-angular-radps", "W",
                          "turn-rate limit (default p3dx.max_angular_radps, 1.0)");
  command_line->AddOption("command-timeout-s", "S",
                          "stop when no VELOCITY_COMMAND for this long (default 0.5)");
}

void ApplyP3dxDriverCommandLine(const CommandLine& command_line, P3dxDriverOptions* options) {
  if (auto v = command_line.Value("port")) options->port = *v;
  if (auto v = command_line.IntValue("baud")) {
    if (*v < 1 || *v > kMaxBaud) throw UsageError("--baud must be a rate from 1 to 10000000");
    options->baud = static_cast<int>(*v);
  }
  if (auto v = command_line.DoubleValue("max-linear-mps")) options->max_linear_mps = *v;
  if (auto v = command_line.DoubleValue("max-angular-radps")) options->max_angular_radps = *v;
  if (auto v = command_line.DoubleValue("command-timeout-s")) options->command_timeout_s = *v;
  try {
    ValidateP3dxDriverOptions(*options);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

void CheckCommandAuthenticationForBus(const P3dxDriverOptions& options,
                                      const std::string& lcm_url) {
  if (options.command_authentication != P3dxDriverOptions::CommandAuthentication::kNone) return;
  if (!IsLocalOnly(ParseLcmUrl(lcm_url))) {
    throw std::invalid_argument(
        "p3dx.command_authentication: none is for a bus whose packets stay on this computer "
        "(udpm://...?ttl=0), not '" +
        lcm_url + "': give the robot a command key instead (docs/robot.md)");
  }
  if (!options.command_key_file.empty()) {
    throw std::invalid_argument(
        "p3dx.command_authentication: none and p3dx.command_key_file exclude each other");
  }
}

void ValidateP3dxDriverOptions(const P3dxDriverOptions& o) {
  auto positive = [](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw std::invalid_argument(std::string(name) + " must be a positive number");
    }
  };
  // Durations become microseconds in int64_t: an hour is far beyond any sensible value and far
  // below an overflow.
  auto duration = [&positive](double value, const char* name) {
    positive(value, name);
    if (value > 3600.0) throw std::invalid_argument(std::string(name) + " above 3600 s");
  };
  CheckEndpoint(o.port, o.baud);
  positive(o.max_linear_mps, "max_linear_mps");
  positive(o.max_angular_radps, "max_angular_radps");
  duration(o.command_timeout_s, "command_timeout_s");
  duration(o.pulse_interval_s, "pulse_interval_s");
  duration(o.sync_reply_timeout_s, "sync_reply_timeout_s");
  duration(o.sip_timeout_s, "sip_timeout_s");
  duration(o.reconnect_initial_s, "reconnect_initial_s");
  duration(o.reconnect_max_s, "reconnect_max_s");
  duration(o.status_period_s, "status_period_s");
  if (o.sync_attempts < 1) throw std::invalid_argument("sync_attempts must be at least 1");
  if (o.reconnect_max_s < o.reconnect_initial_s) {
    throw std::invalid_argument("reconnect_max_s must not be less than reconnect_initial_s");
  }
  if (o.pulse_interval_s >= 2.0) {
    throw std::invalid_argument(
        "pulse_interval_s must be below the firmware watchdog's 2 s, or the robot stops");
  }
  // VEL carries at most 32767 mm/s and RVEL 32767 deg/s; the P3-DX tops out near 1.2 m/s.
  if (o.max_linear_mps > 2.0) throw std::invalid_argument("max_linear_mps above 2.0 m/s");
  if (o.max_angular_radps > 6.0) throw std::invalid_argument("max_angular_radps above 6.0 rad/s");
  if (!(o.command_max_age_s > 0.0 && o.command_max_age_s <= 60.0)) {
    throw std::invalid_argument("command_max_age_s must be in (0, 60] s");
  }
  if (!o.subclass.empty() && !P3dxConversionForSubclass(o.subclass)) {
    throw std::invalid_argument("subclass '" + o.subclass +
                                "' has no conversion factors (use p3dx or p3dx-sh)");
  }
}

}  // namespace slammtt
