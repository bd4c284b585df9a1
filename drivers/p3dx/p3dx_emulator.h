// The P3-DX emulator: a P3dxRobotModel served on a pseudo-terminal (a driver opens /dev/pts/N, or
// a stable symlink to it, as it would the robot's USB-serial adapter) or on a TCP port (as a
// ser2net bridge would serve the robot), with a schedule of faults. slammtt-p3dx-emulator runs it
// from the command line; tests run it in a thread and inject faults through WithModel().
//
// The emulator is a device, not a processing stage: it runs on the host's monotonic clock.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "drivers/common/fd_byte_stream.h"
#include "drivers/common/pty_device.h"
#include "drivers/common/tcp_link.h"
#include "drivers/p3dx/p3dx_robot_model.h"

namespace slammtt {

// One scheduled fault: "KIND@SECONDS[:ARG]" on the command line.
struct P3dxEmulatorFault {
  enum class Kind {
    kGarbage,      // ARG random bytes (default 64)
    kBadChecksum,  // the next ARG packets carry a wrong checksum (default 1)
    kDrop,         // ARG bytes vanish from the middle of the next packet(s) (default 4)
    kShort,        // the next ARG SIPs are cut to 12 bytes in a valid frame (default 1)
    kTruncate,     // the next ARG packets stop halfway (default 1)
    kSilence,      // ARG seconds without a byte out or in (default 3)
    kMute,         // ARG seconds without a byte out while everything heard is carried out
                   // (default 3): a robot whose transmit line failed
    kDisconnect,   // the link goes away for ARG seconds (default 2): pty hung up and created
                   // anew (new /dev/pts/N, the symlink follows), TCP client dropped and the
                   // port closed
    kBumper,       // ARG "LEFT,RIGHT" 7-bit bumper masks (default 1,0)
    kStall,        // ARG "LEFT,RIGHT" 0/1 wheel stall flags (default 1,0)
  };
  Kind kind = Kind::kGarbage;
  double at_s = 0.0;  // seconds after the emulator started
  std::string argument;
};

// Parses "KIND@SECONDS[:ARG]"; std::invalid_argument with one line on anything else.
P3dxEmulatorFault ParseP3dxEmulatorFault(const std::string& text);

struct P3dxEmulatorOptions {
  P3dxRobotModelOptions robot;
  // Exactly one of: a pty (optionally published as a symlink), or a TCP port.
  bool use_pty = true;
  std::string pty_link;             // "" = no symlink
  std::string tcp_bind_host = "127.0.0.1";
  int tcp_port = 0;                 // 0 = any free port
  std::vector<P3dxEmulatorFault> faults;
};

class P3dxEmulator {
 public:
  // Creates the pty or starts listening; throws LinkError when it cannot.
  explicit P3dxEmulator(const P3dxEmulatorOptions& options);
  ~P3dxEmulator();

  // What a driver is given: the symlink (or /dev/pts/N) of the pty, or "tcp://HOST:PORT".
  std::string Endpoint() const;

  // Serves until `stop_requested()` returns true (asked at least every 20 ms).
  void Run(const std::function<bool()>& stop_requested);

  // Runs `f` on the robot with the emulator's lock held (from any thread): fault injection
  // and inspection in tests.
  template <class F>
  auto WithModel(F&& f) {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(model_);
  }
  // Same clock the model runs on (for SilenceFor and friends).
  static int64_t NowUs();

  int64_t bytes_dropped() const { return bytes_dropped_.load(); }
  int64_t host_connections() const { return host_connections_.load(); }

 private:
  void ApplyDueFaults(int64_t now_us);
  void Disconnect(int64_t now_us, int64_t duration_us);
  void Reconnect();
  void ServeOnce(int64_t now_us);

  P3dxEmulatorOptions options_;
  std::mutex mutex_;
  P3dxRobotModel model_;
  std::unique_ptr<PtyDevice> pty_;
  std::unique_ptr<TcpDeviceServer> server_;
  std::unique_ptr<FdByteStream> client_;
  int64_t start_us_ = 0;
  size_t next_fault_ = 0;
  int64_t disconnected_until_us_ = 0;
  bool disconnected_ = false;
  std::atomic<int64_t> bytes_dropped_{0};
  std::atomic<int64_t> host_connections_{0};
};

}  // namespace slammtt
