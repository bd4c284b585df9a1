#include "drivers/p3dx/p3dx_emulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "drivers/common/fault_schedule.h"
#include "runtime/log.h"

namespace slammtt {
namespace {

struct FaultName {
  const char* name;
  P3dxEmulatorFault::Kind kind;
};
constexpr FaultName kFaultNames[] = {
    {"garbage", P3dxEmulatorFault::Kind::kGarbage},
    {"bad-checksum", P3dxEmulatorFault::Kind::kBadChecksum},
    {"drop", P3dxEmulatorFault::Kind::kDrop},
    {"short", P3dxEmulatorFault::Kind::kShort},
    {"truncate", P3dxEmulatorFault::Kind::kTruncate},
    {"silence", P3dxEmulatorFault::Kind::kSilence},
    {"mute", P3dxEmulatorFault::Kind::kMute},
    {"disconnect", P3dxEmulatorFault::Kind::kDisconnect},
    {"bumper", P3dxEmulatorFault::Kind::kBumper},
    {"stall", P3dxEmulatorFault::Kind::kStall},
};

const char* NameOf(P3dxEmulatorFault::Kind kind) {
  for (const FaultName& entry : kFaultNames) {
    if (entry.kind == kind) return entry.name;
  }
  return "?";
}

// "A,B" as two integers.
std::pair<int, int> PairOr(const std::string& text, std::pair<int, int> fallback,
                           const std::string& fault) {
  if (text.empty()) return fallback;
  const size_t comma = text.find(',');
  if (comma == std::string::npos) {
    throw std::invalid_argument("fault '" + fault + "': expected LEFT,RIGHT, got '" + text + "'");
  }
  return {static_cast<int>(FaultNumber(text.substr(0, comma), 0, fault)),
          static_cast<int>(FaultNumber(text.substr(comma + 1), 0, fault))};
}

}  // namespace

P3dxEmulatorFault ParseP3dxEmulatorFault(const std::string& text) {
  std::vector<std::string> names;
  for (const FaultName& entry : kFaultNames) names.push_back(entry.name);
  const ScheduledFault parsed = ParseScheduledFault(text, names);
  P3dxEmulatorFault fault;
  for (const FaultName& entry : kFaultNames) {
    if (parsed.kind == entry.name) fault.kind = entry.kind;
  }
  fault.at_s = parsed.at_s;
  fault.argument = parsed.argument;
  // Check the argument now rather than when the fault fires.
  switch (fault.kind) {
    case P3dxEmulatorFault::Kind::kBumper:
    case P3dxEmulatorFault::Kind::kStall:
      PairOr(fault.argument, {0, 0}, text);
      break;
    default:
      FaultNumber(fault.argument, 0.0, text);
      break;
  }
  return fault;
}

int64_t P3dxEmulator::NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

P3dxEmulator::P3dxEmulator(const P3dxEmulatorOptions& options)
    : options_(options), model_(options.robot) {
  std::stable_sort(options_.faults.begin(), options_.faults.end(),
                   [](const P3dxEmulatorFault& a, const P3dxEmulatorFault& b) { return a.at_s < b.at_s; });
  if (options_.use_pty) {
    pty_ = std::make_unique<PtyDevice>();
    if (!options_.pty_link.empty()) pty_->PublishLink(options_.pty_link);
  } else {
    server_ = std::make_unique<TcpDeviceServer>(options_.tcp_bind_host, options_.tcp_port);
  }
  start_us_ = NowUs();
  model_.AdvanceTo(start_us_);
}

P3dxEmulator::~P3dxEmulator() = default;

std::string P3dxEmulator::Endpoint() const {
  if (server_) return server_->Endpoint();
  if (!options_.pty_link.empty()) return options_.pty_link;
  return pty_ ? pty_->slave_path() : std::string();
}

void P3dxEmulator::ApplyDueFaults(int64_t now_us) {
  while (next_fault_ < options_.faults.size() &&
         now_us - start_us_ >= std::llround(options_.faults[next_fault_].at_s * 1e6)) {
    const P3dxEmulatorFault& fault = options_.faults[next_fault_++];
    const std::string& arg = fault.argument;
    LogInfo() << "fault at " << fault.at_s << " s: " << NameOf(fault.kind)
              << (arg.empty() ? "" : " " + arg);
    std::lock_guard<std::mutex> lock(mutex_);
    switch (fault.kind) {
      case P3dxEmulatorFault::Kind::kGarbage:
        model_.InjectGarbage(static_cast<int>(FaultNumber(arg, 64, arg)));
        break;
      case P3dxEmulatorFault::Kind::kBadChecksum:
        model_.CorruptNextChecksums(static_cast<int>(FaultNumber(arg, 1, arg)));
        break;
      case P3dxEmulatorFault::Kind::kDrop:
        model_.DropNextBytes(static_cast<int>(FaultNumber(arg, 4, arg)));
        break;
      case P3dxEmulatorFault::Kind::kShort:
        model_.SendShortSips(static_cast<int>(FaultNumber(arg, 1, arg)));
        break;
      case P3dxEmulatorFault::Kind::kTruncate:
        model_.TruncateNextPackets(static_cast<int>(FaultNumber(arg, 1, arg)));
        break;
      case P3dxEmulatorFault::Kind::kSilence:
        model_.SilenceFor(std::llround(FaultNumber(arg, 3.0, arg) * 1e6), now_us);
        break;
      case P3dxEmulatorFault::Kind::kMute:
        model_.MuteFor(std::llround(FaultNumber(arg, 3.0, arg) * 1e6), now_us);
        break;
      case P3dxEmulatorFault::Kind::kDisconnect:
        Disconnect(now_us, std::llround(FaultNumber(arg, 2.0, arg) * 1e6));
        break;
      case P3dxEmulatorFault::Kind::kBumper: {
        const auto bits = PairOr(arg, {1, 0}, arg);
        model_.SetBumpers(bits.first, bits.second);
        break;
      }
      case P3dxEmulatorFault::Kind::kStall: {
        const auto flags = PairOr(arg, {1, 0}, arg);
        model_.SetWheelStall(flags.first != 0, flags.second != 0);
        break;
      }
    }
  }
}

void P3dxEmulator::Disconnect(int64_t now_us, int64_t duration_us) {
  // Called with mutex_ held.
  disconnected_ = true;
  disconnected_until_us_ = now_us + duration_us;
  model_.HostDisconnected();
  if (pty_) {
    pty_.reset();  // the host sees a hangup, as when the USB adapter is pulled
  } else {
    client_.reset();
    server_->StopListening();
  }
}

void P3dxEmulator::Reconnect() {
  disconnected_ = false;
  if (options_.use_pty) {
    pty_ = std::make_unique<PtyDevice>();
    if (!options_.pty_link.empty()) pty_->PublishLink(options_.pty_link);
    LogInfo() << "plugged in again as " << pty_->slave_path()
              << (options_.pty_link.empty() ? "" : " (" + options_.pty_link + ")");
  } else {
    server_->Listen();
    LogInfo() << "listening again on " << server_->Endpoint();
  }
}

void P3dxEmulator::Run(const std::function<bool()>& stop_requested) {
  uint8_t buffer[512];
  while (!stop_requested()) {
    const int64_t now = NowUs();
    ApplyDueFaults(now);
    if (disconnected_) {
      if (now >= disconnected_until_us_) {
        Reconnect();
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        std::lock_guard<std::mutex> lock(mutex_);
        model_.AdvanceTo(NowUs());
        model_.TakeOutput();  // sent into an unplugged cable
        continue;
      }
    }
    if (server_) {
      auto client = server_->Accept(client_ ? 0 : 20);
      if (client) {
        client_ = std::move(client);
        ++host_connections_;
        std::lock_guard<std::mutex> lock(mutex_);
        model_.HostDisconnected();  // a new host starts with a fresh line
      }
    }
    FdByteStream* link = pty_ ? &pty_->stream() : client_.get();
    if (link == nullptr) {
      std::lock_guard<std::mutex> lock(mutex_);
      model_.AdvanceTo(NowUs());
      model_.TakeOutput();
      continue;
    }
    try {
      std::vector<uint8_t> out;
      int64_t next_event = 0;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        model_.AdvanceTo(NowUs());
        out = model_.TakeOutput();
        next_event = model_.NextEventUs();
      }
      if (!out.empty()) {
        const size_t written = link->WriteAvailable(out.data(), out.size());
        bytes_dropped_ += static_cast<int64_t>(out.size() - written);
      }
      const int64_t wait_us = std::clamp<int64_t>(next_event - NowUs(), 0, 20000);
      const size_t n = link->Read(buffer, sizeof buffer, static_cast<int>((wait_us + 999) / 1000));
      if (n > 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        model_.Receive(buffer, n, NowUs());
      }
    } catch (const LinkError& e) {
      LogInfo() << "host went away: " << e.what();
      std::lock_guard<std::mutex> lock(mutex_);
      model_.HostDisconnected();
      if (server_) {
        client_.reset();
      } else {
        // A pty master fails only if the pty itself is gone: make a new one.
        pty_.reset();
        disconnected_ = true;
        disconnected_until_us_ = NowUs() + 100000;
      }
    }
  }
}

}  // namespace slammtt
