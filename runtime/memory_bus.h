// The Bus (bus.h) in memory, for tests and for running several stages in one process: a
// publish appends the message to a queue, and Handle() delivers the messages that were queued
// when it was called, in publish order (what a handler publishes meanwhile waits for the next
// Handle(), as it would on LCM). Nothing leaves the process; deterministic.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "runtime/bus.h"

namespace slammtt {

class MemoryBus : public Bus {
 public:
  void Publish(const std::string& channel, const void* data, int size) override;
  bool HasWaiting() const override { return !queue_.empty(); }

  int64_t messages_published() const { return messages_published_; }

 protected:
  void StartReceiving(const std::string& /*channel*/) override {}
  int DeliverWaiting() override;

 private:
  struct Message {
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  std::deque<Message> queue_;
  int64_t messages_published_ = 0;
};

}  // namespace slammtt
