#include "runtime/bus.h"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "runtime/log.h"
#include "runtime/shutdown.h"

namespace slammtt {

int Bus::SubscribeBytes(const std::string& channel, BytesHandler handler) {
  if (!handler) throw std::invalid_argument("Bus::SubscribeBytes: no handler for " + channel);
  subscriptions_.push_back(Subscription{
      next_id_, channel, std::make_shared<const BytesHandler>(std::move(handler))});
  if (std::find(receiving_.begin(), receiving_.end(), channel) == receiving_.end()) {
    receiving_.push_back(channel);
    StartReceiving(channel);
  }
  return next_id_++;
}

void Bus::Unsubscribe(int id) {
  // Emptied, not erased: Dispatch() may be iterating (erased in Handle(), outside any dispatch).
  for (Subscription& s : subscriptions_) {
    if (s.id == id) s.handler = nullptr;
  }
}

void Bus::Dispatch(const std::string& channel, const void* data, int size) {
  // By index: a handler may subscribe (push_back) while we iterate.
  for (size_t k = 0; k < subscriptions_.size(); ++k) {
    if (subscriptions_[k].channel != channel || !subscriptions_[k].handler) continue;
    try {
      // Held here: the handler may subscribe, which moves the vector's elements.
      const std::shared_ptr<const BytesHandler> handler = subscriptions_[k].handler;
      (*handler)(channel, data, size);
    } catch (...) {
      ++handler_exceptions_;
      if (!first_error_) first_error_ = std::current_exception();
    }
  }
}

void Bus::CountUndecodable(const std::string& channel, int64_t count_on_subscription) {
  ++undecodable_messages_;
  if (IsReportable(count_on_subscription)) {
    LogWarning() << channel << ": undecodable message skipped (" << count_on_subscription
                 << " so far)";
  }
}

int Bus::Handle() {
  subscriptions_.erase(std::remove_if(subscriptions_.begin(), subscriptions_.end(),
                                      [](const Subscription& s) { return !s.handler; }),
                       subscriptions_.end());
  const int delivered = DeliverWaiting();
  if (first_error_) {
    std::exception_ptr error = first_error_;
    first_error_ = nullptr;
    std::rethrow_exception(error);
  }
  return delivered;
}

int Bus::HandleTimeout(int timeout_ms) {
  if (timeout_ms < 0) throw std::invalid_argument("Bus::HandleTimeout: negative timeout");
  if (!HasWaiting()) {
    pollfd fds[2] = {{ShutdownFd(), POLLIN, 0},
                     {HasSubscriptions() ? WaitDescriptor() : -1, POLLIN, 0}};
    const nfds_t count = fds[1].fd >= 0 ? 2 : 1;
    if (poll(fds, count, timeout_ms) < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("poll failed: ") + std::strerror(errno));
    }
  }
  return Handle();
}

}  // namespace slammtt
