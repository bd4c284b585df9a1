#include "runtime/lcm_bus.h"

#include <poll.h>

#include <cerrno>
#include <cstring>
#include <regex>
#include <stdexcept>

#include "runtime/log.h"

namespace slammtt {

LcmBus::LcmBus(const std::string& url) : url_(url), lcm_(OpenLcm(url)) {}

LcmBus::~LcmBus() = default;

void LcmBus::Publish(const std::string& channel, const void* data, int size) {
  if (lcm_->publish(channel, data, static_cast<unsigned int>(size)) == 0) return;
  ++failed_publishes_;
  if (IsReportable(failed_publishes_)) {
    LogWarning() << "LCM publish on " << channel << " failed (" << failed_publishes_
                 << " failed publishes so far); the message is lost";
  }
}

int LcmBus::WaitDescriptor() const { return lcm_->getFileno(); }

void LcmBus::StartReceiving(const std::string& channel) {
  // LCM takes a channel as a regular expression (anchored); ours are exact names, so the
  // characters a regex gives a meaning to are escaped.
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  const std::string pattern = std::regex_replace(channel, special, R"(\$&)");
  lcm_->subscribeFunction(pattern, &LcmBus::OnMessage, this);
}

void LcmBus::OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel,
                       LcmBus* self) {
  self->Dispatch(channel, buffer->data, static_cast<int>(buffer->data_size));
}

int LcmBus::DeliverWaiting() {
  // lcm::LCM::handle() blocks until a message is there: ask poll() first, and take everything
  // that waits (one message per handle()).
  if (!HasSubscriptions()) return 0;  // and LCM's receive thread is never started
  int delivered = 0;
  pollfd fd = {lcm_->getFileno(), POLLIN, 0};
  while (true) {
    const int ready = poll(&fd, 1, 0);
    if (ready < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("poll failed: ") + std::strerror(errno));
    }
    if (ready == 0 || (fd.revents & POLLIN) == 0) return delivered;
    if (lcm_->handle() != 0) throw std::runtime_error("LCM failed while receiving");
    ++delivered;
    if (handler_failed()) return delivered;
  }
}

}  // namespace slammtt
