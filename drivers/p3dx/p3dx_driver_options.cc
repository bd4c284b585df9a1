#include "drivers/p3dx/p3dx_driver_options.h"

#include "drivers/p3dx/p3dx_odometry.h"

namespace slammtt {

const char* CommandAuthenticationName(P3dxDriverOptions::CommandAuthentication mode) {
  return mode == P3dxDriverOptions::CommandAuthentication::kNone ? "none" : "hmac-sha256";
}

void VisitP3dxDriverOptions(OptionVisitor* v, P3dxDriverOptions* o) {
  using R = OptionRange;
  // Durations become microseconds in int64_t: an hour is far beyond any sensible value and far
  // below an overflow.
  const R duration = R::AboveUpTo(0, 3600);
  v->String("port", &o->port, "serial port (symlinks resolved) or `tcp://HOST:PORT`");
  v->Int("baud", &o->baud, R::Between(1, 10000000),
         "serial rate (ARCOS default; ignored over TCP)");
  // VEL carries at most 32767 mm/s and RVEL 32767 deg/s; the P3-DX tops out near 1.2 m/s.
  v->Double("max_linear_mps", &o->max_linear_mps, R::AboveUpTo(0, 2),
            "speed limit applied to commands");
  v->Double("max_angular_radps", &o->max_angular_radps, R::AboveUpTo(0, 6),
            "turn-rate limit applied to commands, rad/s");
  v->Double("command_timeout_s", &o->command_timeout_s, duration,
            "stop when no command came for this long");
  v->Double("pulse_interval_s", &o->pulse_interval_s, R::Open(0, 2),
            "PULSE / repeat VEL after this long without sending (below the firmware "
            "watchdog's 2 s, or the robot stops)");
  v->Double("sync_reply_timeout_s", &o->sync_reply_timeout_s, duration,
            "re-send an unanswered SYNC");
  v->Int("sync_attempts", &o->sync_attempts, R::Between(1, 1000),
         "unanswered SYNCs before the link is reopened");
  v->Double("sip_timeout_s", &o->sip_timeout_s, duration, "no valid SIP for this long: link lost");
  v->Double("reconnect_initial_s", &o->reconnect_initial_s, duration,
            "first reopen delay, doubling ...");
  v->Double("reconnect_max_s", &o->reconnect_max_s, duration, "... up to this");
  v->String("subclass", &o->subclass,
            "force the conversion factors (`p3dx`, `p3dx-sh`); empty: from the SYNC2 reply");
  v->Bool("enable_motors", &o->enable_motors, "send ENABLE 1 after OPEN");
  v->Double("status_period_s", &o->status_period_s, duration, "BASE_STATUS period");
  int authentication = static_cast<int>(o->command_authentication);
  v->Choice("command_authentication", &authentication, {"hmac-sha256", "none"},
            "`hmac-sha256`: only signed commands move the robot; `none`: every command does "
            "(only with a bus that keeps to the computer: memq, or udpm with ttl=0)");
  o->command_authentication =
      static_cast<P3dxDriverOptions::CommandAuthentication>(authentication);
  v->String("command_key_file", &o->command_key_file,
            "the key shared with the base stations (64 hexadecimal digits, `slammtt-command-key "
            "new FILE`), a file other users can neither read nor write; empty: no key, every "
            "command refused");
  v->Double("command_max_age_s", &o->command_max_age_s, R::AboveUpTo(0, 60),
            "freshness window of a signed command's `utime`, either way");
}

std::string CheckP3dxDriverOptions(const P3dxDriverOptions& options) {
  P3dxDriverOptions o = options;
  OptionRangeCheck check;
  VisitP3dxDriverOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  if (o.reconnect_max_s < o.reconnect_initial_s) {
    return "reconnect_max_s must not be less than reconnect_initial_s";
  }
  if (!o.subclass.empty() && !P3dxConversionForSubclass(o.subclass)) {
    return "subclass '" + o.subclass + "' has no conversion factors (use p3dx or p3dx-sh)";
  }
  return "";
}

std::string P3dxDriverOptionsTable() {
  P3dxDriverOptions defaults;
  OptionsMarkdownTable table;
  VisitP3dxDriverOptions(&table, &defaults);
  return table.Table();
}

}  // namespace slammtt
