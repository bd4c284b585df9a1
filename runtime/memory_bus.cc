#include "runtime/memory_bus.h"

#include <stdexcept>
#include <utility>

namespace slammtt {

void MemoryBus::Publish(const std::string& channel, const void* data, int size) {
  if (size < 0 || (data == nullptr && size > 0)) {
    throw std::invalid_argument("MemoryBus: publish of a negative size or without data");
  }
  const auto* bytes = static_cast<const uint8_t*>(data);
  queue_.push_back(Message{channel, std::vector<uint8_t>(bytes, bytes + size)});
  ++messages_published_;
}

int MemoryBus::DeliverWaiting() {
  const size_t waiting = queue_.size();
  int delivered = 0;
  for (size_t k = 0; k < waiting && !handler_failed(); ++k) {
    const Message message = std::move(queue_.front());
    queue_.pop_front();
    Dispatch(message.channel, message.bytes.data(), static_cast<int>(message.bytes.size()));
    ++delivered;
  }
  return delivered;
}

}  // namespace slammtt
