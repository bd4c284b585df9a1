// Puts an RplidarDeviceModel on a link a driver can open: a pseudo-terminal (the driver opens
// it as the serial port of a real A2, through libserialport under pty-run) or a TCP port (as a
// serial-to-network bridge would offer it). Runs on a thread of its own (tests) or on the
// caller's thread (the emulator program). Fault injection is thread-safe.
//
// Disconnect(duration): the device goes away and comes back, as a pulled and replugged USB
// adapter: over a pty the pseudo-terminal is closed (the host sees a hangup) and a new one is
// created after `duration`, re-published at the same link path; over TCP the client is dropped
// and connections are refused for `duration`. In both cases the device power-cycles.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "drivers/common/fd_byte_stream.h"
#include "drivers/common/pty_device.h"
#include "drivers/common/tcp_link.h"
#include "drivers/rplidar/rplidar_device_model.h"

namespace slammtt {
namespace rplidar {

struct EmulatorTransportOptions {
  enum class Kind { kPty, kTcp };
  Kind kind = Kind::kPty;
  // pty: a symlink kept pointing at the current /dev/pts/N ("" = none; endpoint() is then the
  // /dev/pts path, which changes after a Disconnect()).
  std::string link_path;
  // tcp: where to listen; port 0 picks a free port.
  std::string bind_host = "127.0.0.1";
  int tcp_port = 0;
};

struct EmulatorServerStats {
  RplidarDeviceStats device;
  int64_t host_connections = 0;  // TCP clients accepted (pty: 0)
  int64_t disconnects = 0;
  int64_t overflow_bytes = 0;    // beyond 64 kB unread by the host: lost
};

class RplidarEmulatorServer {
 public:
  // Creates the pty or starts listening. Throws LinkError when it cannot.
  RplidarEmulatorServer(const RplidarDeviceOptions& device,
                        const EmulatorTransportOptions& transport);
  ~RplidarEmulatorServer();
  RplidarEmulatorServer(const RplidarEmulatorServer&) = delete;
  RplidarEmulatorServer& operator=(const RplidarEmulatorServer&) = delete;

  // What a driver is given: the link path, the /dev/pts path, or tcp://HOST:PORT.
  std::string endpoint() const;

  // Serves on a background thread until Stop() (or destruction).
  void Start();
  void Stop();
  // Serves on the calling thread until `should_stop()` is true (checked every few ms).
  void Run(const std::function<bool()>& should_stop);

  void InjectGarbage(size_t bytes);
  void CorruptPackets(int count);
  void DropBytes(int count);
  void Silence(int duration_ms);
  void Mute(int duration_ms);  // transmits nothing, still carries out requests
  void Disconnect(int duration_ms);
  void SetHealth(const DeviceHealth& health, bool persists_after_reset);

  EmulatorServerStats stats() const;

 private:
  void ServeOnce();
  void OpenDevice();
  void CloseDevice();
  FdByteStream* Link();
  int64_t Now() const;

  RplidarDeviceOptions device_options_;
  EmulatorTransportOptions transport_;
  mutable std::mutex mutex_;
  RplidarDeviceModel model_;
  std::unique_ptr<PtyDevice> pty_;
  std::unique_ptr<TcpDeviceServer> tcp_server_;
  std::unique_ptr<FdByteStream> tcp_client_;
  std::string pty_path_;
  int64_t reconnect_at_us_ = -1;
  int pending_disconnect_ms_ = -1;
  int64_t next_dtr_poll_us_ = 0;
  std::vector<uint8_t> pending_output_;  // transmitted, not yet taken by the link
  EmulatorServerStats stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rplidar
}  // namespace slammtt
