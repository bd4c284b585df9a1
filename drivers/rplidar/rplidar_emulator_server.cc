#include "drivers/rplidar/rplidar_emulator_server.h"

#include <time.h>

#include <chrono>

#include "drivers/common/byte_stream.h"

namespace slammtt {
namespace rplidar {
namespace {

constexpr int kPollMs = 2;
constexpr int64_t kDtrPollUs = 5000;
// What the USB adapter and the kernel would buffer for a host that reads late: 64 kB, about
// 6 s of scan data at 115200 baud. A pty alone holds about 4 kB, which a test machine under
// load can overrun; that would test the machine, not the protocol.
constexpr size_t kMaxPendingBytes = 64 * 1024;

}  // namespace

RplidarEmulatorServer::RplidarEmulatorServer(const RplidarDeviceOptions& device,
                                             const EmulatorTransportOptions& transport)
    : device_options_(device), transport_(transport), model_(device) {
  OpenDevice();
}

RplidarEmulatorServer::~RplidarEmulatorServer() { Stop(); }

int64_t RplidarEmulatorServer::Now() const {
  struct timespec now = {};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<int64_t>(now.tv_sec) * 1000000 + now.tv_nsec / 1000;
}

void RplidarEmulatorServer::OpenDevice() {
  if (transport_.kind == EmulatorTransportOptions::Kind::kPty) {
    pty_ = std::make_unique<PtyDevice>();
    pty_path_ = pty_->slave_path();
    if (!transport_.link_path.empty()) pty_->PublishLink(transport_.link_path);
  } else if (!tcp_server_) {
    tcp_server_ = std::make_unique<TcpDeviceServer>(transport_.bind_host, transport_.tcp_port);
    transport_.tcp_port = tcp_server_->port();
  } else {
    tcp_server_->Listen();
  }
}

void RplidarEmulatorServer::CloseDevice() {
  pty_.reset();
  tcp_client_.reset();
  if (tcp_server_) tcp_server_->StopListening();
}

std::string RplidarEmulatorServer::endpoint() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (transport_.kind == EmulatorTransportOptions::Kind::kTcp) return tcp_server_->Endpoint();
  return transport_.link_path.empty() ? pty_path_ : transport_.link_path;
}

FdByteStream* RplidarEmulatorServer::Link() {
  if (pty_) return &pty_->stream();
  return tcp_client_.get();
}

void RplidarEmulatorServer::ServeOnce() {
  uint8_t buffer[1024];
  size_t got = 0;
  FdByteStream* link = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int64_t now = Now();
    if (pending_disconnect_ms_ >= 0) {
      CloseDevice();
      pending_output_.clear();
      ++stats_.disconnects;
      model_.PowerCycle(now);
      reconnect_at_us_ = now + int64_t{pending_disconnect_ms_} * 1000;
      pending_disconnect_ms_ = -1;
    }
    if (reconnect_at_us_ >= 0) {
      if (now < reconnect_at_us_) {
        link = nullptr;
      } else {
        reconnect_at_us_ = -1;
        OpenDevice();
      }
    }
    if (reconnect_at_us_ < 0 && tcp_server_) {
      if (auto client = tcp_server_->Accept(0)) {
        tcp_client_ = std::move(client);  // a new host wins over the old connection
        pending_output_.clear();
        ++stats_.host_connections;
      }
    }
    if (reconnect_at_us_ < 0) link = Link();
  }
  if (link == nullptr) {
    std::this_thread::sleep_for(std::chrono::milliseconds(kPollMs));
    return;
  }
  // The link objects change only on this thread (Disconnect() only asks), so reading
  // without the lock is safe.
  try {
    got = link->Read(buffer, sizeof buffer, kPollMs);
  } catch (const LinkError&) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (link == tcp_client_.get()) tcp_client_.reset();  // the host closed its connection
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const int64_t now = Now();
  if (got > 0) model_.OnHostBytes(buffer, got, now);
  if (pty_ && now >= next_dtr_poll_us_) {
    model_.SetHostDtr(pty_->HostDtr(), now);
    next_dtr_poll_us_ = now + kDtrPollUs;
  }
  const std::vector<uint8_t> out = model_.TakeOutput(now);
  pending_output_.insert(pending_output_.end(), out.begin(), out.end());
  if (pending_output_.size() > kMaxPendingBytes) {
    // The host has not read for seconds: what the adapter could not hold is lost.
    const size_t lost = pending_output_.size() - kMaxPendingBytes;
    pending_output_.erase(pending_output_.begin(),
                          pending_output_.begin() + static_cast<std::ptrdiff_t>(lost));
    stats_.overflow_bytes += static_cast<int64_t>(lost);
  }
  if (pending_output_.empty()) return;
  try {
    const size_t sent = link->WriteAvailable(pending_output_.data(), pending_output_.size());
    pending_output_.erase(pending_output_.begin(),
                          pending_output_.begin() + static_cast<std::ptrdiff_t>(sent));
  } catch (const LinkError&) {
    if (link == tcp_client_.get()) tcp_client_.reset();
    pending_output_.clear();
  }
}

void RplidarEmulatorServer::Run(const std::function<bool()>& should_stop) {
  while (!should_stop() && !stop_) ServeOnce();
}

void RplidarEmulatorServer::Start() {
  if (thread_.joinable()) return;
  stop_ = false;
  thread_ = std::thread([this] { Run([] { return false; }); });
}

void RplidarEmulatorServer::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void RplidarEmulatorServer::InjectGarbage(size_t bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.InjectGarbage(bytes);
}

void RplidarEmulatorServer::CorruptPackets(int count) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.CorruptPackets(count);
}

void RplidarEmulatorServer::DropBytes(int count) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.DropBytes(count);
}

void RplidarEmulatorServer::Silence(int duration_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.Silence(int64_t{duration_ms} * 1000, Now());
}

void RplidarEmulatorServer::Mute(int duration_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.Mute(int64_t{duration_ms} * 1000, Now());
}

void RplidarEmulatorServer::Disconnect(int duration_ms) {
  // Carried out by the serving thread, the only one that touches the link objects.
  std::lock_guard<std::mutex> lock(mutex_);
  pending_disconnect_ms_ = duration_ms;
}

void RplidarEmulatorServer::SetHealth(const DeviceHealth& health, bool persists_after_reset) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_.SetHealth(health, persists_after_reset);
}

EmulatorServerStats RplidarEmulatorServer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  EmulatorServerStats copy = stats_;
  copy.device = model_.stats();
  return copy;
}

}  // namespace rplidar
}  // namespace slammtt
