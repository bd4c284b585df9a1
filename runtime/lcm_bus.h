// The Bus (bus.h) on LCM: what a live process publishes and receives. Opened from a URL
// (ResolveLcmUrl in lcm_io.h; the default keeps every packet on the host: ttl=0).
//
// A publish that fails (a transient UDP send error, a full socket buffer) loses that one
// message: it is counted and reported on the 1st, 10th, 100th, ... failure, and the process
// goes on (a driver must not die and stop its device over it); a caller for whom a lost message
// is an error compares failed_publishes() before and after.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <string>

#include "runtime/bus.h"

namespace slammtt {

class LcmBus : public Bus {
 public:
  // Opens the bus at `url` (OpenLcm: a one-line std::runtime_error when it cannot).
  explicit LcmBus(const std::string& url);
  ~LcmBus() override;

  void Publish(const std::string& channel, const void* data, int size) override;
  int WaitDescriptor() const override;

  int64_t failed_publishes() const override { return failed_publishes_; }
  const std::string& url() const { return url_; }

 protected:
  void StartReceiving(const std::string& channel) override;
  int DeliverWaiting() override;

 private:
  static void OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel,
                        LcmBus* self);

  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  int64_t failed_publishes_ = 0;
};

}  // namespace slammtt
