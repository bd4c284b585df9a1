// Shared pieces of the RPLIDAR tests: a virtual clock and an in-memory link to a device model
// (the whole driver lifecycle in virtual time: fast and deterministic), a sink that records
// what the driver publishes, and the room oracle every beam is checked against.
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/rplidar/emulated_room.h"
#include "drivers/rplidar/rplidar_device_model.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/lidar_status_t.hpp"

namespace slammtt {
namespace rplidar {
namespace testing_support {

inline constexpr int64_t kUtimeBase = 1700000000000000;

class VirtualClock : public DriverClock {
 public:
  int64_t NowUtime() override { return kUtimeBase + now_us_; }
  int64_t NowMonotonicUs() override { return now_us_; }
  void SleepUs(int64_t duration_us) override { now_us_ += std::max<int64_t>(0, duration_us); }
  int64_t now_us_ = 1000000;
};

// The host side of a link to `model`, in virtual time: reads advance the clock in 0.5 ms steps
// until the device has transmitted something or the timeout has passed.
class VirtualLink : public ByteStream {
 public:
  // Opening a serial port asserts DTR (on an A2 through its USB adapter: motor stopped).
  VirtualLink(RplidarDeviceModel* model, VirtualClock* clock, const bool* unplugged)
      : model_(model), clock_(clock), unplugged_(unplugged) {
    model_->SetHostDtr(true, clock_->now_us_);
  }

  void Write(const uint8_t* data, size_t size, int) override {
    CheckPlugged();
    model_->OnHostBytes(data, size, clock_->now_us_);
  }
  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override {
    const int64_t end = clock_->now_us_ + int64_t{timeout_ms} * 1000;
    for (;;) {
      CheckPlugged();
      const std::vector<uint8_t> out = model_->TakeOutput(clock_->now_us_);
      pending_.insert(pending_.end(), out.begin(), out.end());
      if (!pending_.empty() || clock_->now_us_ >= end) break;
      clock_->now_us_ += 500;
    }
    const size_t count = std::min(capacity, pending_.size());
    std::copy(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count), buffer);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count));
    return count;
  }
  void FlushInput() override {
    CheckPlugged();
    model_->TakeOutput(clock_->now_us_);
    pending_.clear();
  }
  void SetDtr(bool asserted) override { model_->SetHostDtr(asserted, clock_->now_us_); }
  std::string Describe() const override { return "virtual:rplidar"; }

 private:
  void CheckPlugged() const {
    if (*unplugged_) throw LinkError("virtual:rplidar: unplugged");
  }
  RplidarDeviceModel* model_;
  VirtualClock* clock_;
  const bool* unplugged_;
  std::deque<uint8_t> pending_;
};

// Records what a driver publishes (thread-safe), and when (with a clock).
class RecordingSink : public MessageSink {
 public:
  explicit RecordingSink(DriverClock* clock = nullptr) : clock_(clock) {}
  void Publish(const std::string& channel, const void* data, int size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (channel == "LASER_SCAN") {
      slammtt_msgs::laser_scan_t scan;
      if (Decode(data, size, &scan)) {
        scans_.push_back(scan);
        publish_utimes_.push_back(clock_ != nullptr ? clock_->NowUtime() : 0);
      }
    } else if (channel == "LIDAR_STATUS") {
      slammtt_msgs::lidar_status_t status;
      if (Decode(data, size, &status)) statuses_.push_back(status);
    } else if (channel == "LASER_GEOMETRY") {
      slammtt_msgs::laser_geometry_t geometry;
      if (Decode(data, size, &geometry)) geometries_.push_back(geometry);
    }
    channels_.push_back(channel);
  }
  std::vector<slammtt_msgs::laser_scan_t> scans() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return scans_;
  }
  std::vector<slammtt_msgs::lidar_status_t> statuses() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_;
  }
  std::vector<slammtt_msgs::laser_geometry_t> geometries() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return geometries_;
  }
  // Every channel published on, in order.
  std::vector<std::string> channels() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return channels_;
  }
  void Clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    geometries_.clear();
    channels_.clear();
    scans_.clear();
    statuses_.clear();
    publish_utimes_.clear();
  }
  std::vector<int64_t> publish_utimes() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return publish_utimes_;
  }
  size_t scan_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return scans_.size();
  }
  std::optional<slammtt_msgs::lidar_status_t> last_status() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (statuses_.empty()) return std::nullopt;
    return statuses_.back();
  }

 private:
  DriverClock* clock_;
  mutable std::mutex mutex_;
  std::vector<slammtt_msgs::laser_scan_t> scans_;
  std::vector<int64_t> publish_utimes_;
  std::vector<slammtt_msgs::lidar_status_t> statuses_;
  std::vector<slammtt_msgs::laser_geometry_t> geometries_;
  std::vector<std::string> channels_;
};

// Beams that do not agree with the room: a beam measured what the room has along its direction
// (within `tolerance_m`; the emulator's noise is 5 mm) or it came from bytes that were never a
// measurement. The beam angle is a float; the ray is cast at it and 0.01 degree either side so
// an edge of a pillar cannot fail a correct beam.
inline int CountBeamsDisagreeingWithRoom(const slammtt_msgs::laser_scan_t& scan,
                                         const EmulatedRoom& room, double tolerance_m = 0.03) {
  constexpr double kPi = 3.14159265358979323846;
  int bad = 0;
  for (int i = 0; i < scan.num_beams; ++i) {
    if (!scan.valid[static_cast<size_t>(i)]) continue;
    const double device_deg = -static_cast<double>(scan.angle_rad[static_cast<size_t>(i)]) * 180.0 / kPi;
    bool agrees = false;
    for (double delta : {0.0, -0.01, 0.01}) {
      const std::optional<double> expected = room.CastDeviceRay(device_deg + delta);
      const double measured = static_cast<double>(scan.range_m[static_cast<size_t>(i)]);
      if (expected && std::fabs(*expected - measured) < tolerance_m) {
        agrees = true;
      }
    }
    if (!agrees) ++bad;
  }
  return bad;
}

}  // namespace testing_support
}  // namespace rplidar
}  // namespace slammtt
