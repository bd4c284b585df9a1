// The message bus every process talks through (Drake's DrakeLcmInterface idea): publish bytes or
// a typed message, subscribe to a channel's bytes or to its decoded messages, and handle what
// has arrived, waiting at most a timeout. The backends deliver the bytes: LCM in a live process
// (lcm_bus.h), a queue in memory for tests (memory_bus.h), a log file as the source and/or the
// destination (log_bus.h). A process's loop (event_loop.h) waits on a bus, its timers and its
// file descriptors together.
//
// Handlers run inside Handle()/HandleTimeout(), on the caller's thread, in arrival order; for
// one message, in the order they subscribed. A handler that throws does not unwind through the
// backend (LCM's C dispatch): its exception is kept, the message's other subscriptions get the
// message, and Handle()/HandleTimeout() rethrows it before delivering any later message (those
// wait for the next Handle()). A process that must go on after a handler fails catches in the
// handler (LiveStageRunner does).
//
// A typed subscription decodes with slammtt::Decode (runtime/lcm_io.h: untrusted bytes are a
// counted skip, never a crash): a message that does not decode is counted (per subscription and
// in undecodable_messages()) and reported as "<channel>: undecodable message skipped (N so far)"
// on the 1st, 10th, 100th, ... one; the handler does not see it.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"

namespace slammtt {

class Bus : public MessageSink {
 public:
  // A channel's raw bytes; `data` is valid during the call only.
  using BytesHandler = std::function<void(const std::string& channel, const void* data, int size)>;

  Bus() = default;
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;
  ~Bus() override = default;

  // Publishes `size` bytes on `channel` (MessageSink; PublishMessage() encodes a typed one).
  void Publish(const std::string& channel, const void* data, int size) override = 0;

  // Every message on `channel` (the exact name), as bytes. Returns an id for Unsubscribe().
  int SubscribeBytes(const std::string& channel, BytesHandler handler);

  // Every message on `channel` that decodes as Msg (see above for the ones that do not).
  // Returns an id for Unsubscribe().
  template <class Msg>
  int Subscribe(const std::string& channel, std::function<void(const Msg&)> handler) {
    auto undecodable = std::make_shared<int64_t>(0);
    return SubscribeBytes(channel, [this, handler = std::move(handler), undecodable](
                                const std::string& ch, const void* data, int size) {
      Msg message;
      if (!Decode(data, size, &message)) {
        CountUndecodable(ch, ++*undecodable);
        return;
      }
      handler(message);
    });
  }

  // The subscription's handler is not called again (also when called from a handler).
  void Unsubscribe(int id);

  // Delivers the messages that are waiting, without waiting. Returns how many were delivered.
  // Rethrows the first exception of a handler (above), and throws std::runtime_error when the
  // backend fails (LCM cannot receive).
  int Handle();
  // Waits at most `timeout_ms` (>= 0) for a message, then delivers what is waiting (Handle()).
  // A signal that interrupts the wait ends it early (the caller checks ShutdownRequested()).
  int HandleTimeout(int timeout_ms);

  // A descriptor that poll() reports readable when messages wait (LCM's), or -1 when the
  // backend has none: then HasWaiting() says it. Waited on only once something is subscribed
  // (LCM starts its receive thread when asked for it: a process that only publishes has none).
  virtual int WaitDescriptor() const { return -1; }
  bool HasSubscriptions() const { return !receiving_.empty(); }
  // True when messages wait that no descriptor announces (the in-memory queue, a log source
  // with events left): a loop then does not block.
  virtual bool HasWaiting() const { return false; }

  // Publishes the backend could not send (each message lost; LCM: lcm_bus.h).
  virtual int64_t failed_publishes() const { return 0; }
  // Messages that typed subscriptions could not decode, over all channels.
  int64_t undecodable_messages() const { return undecodable_messages_; }
  // Exceptions thrown by handlers (the first of each message was rethrown; others of the same
  // message were dropped after counting).
  int64_t handler_exceptions() const { return handler_exceptions_; }

 protected:
  // The backend starts receiving `channel` (called once per channel, at its first subscription).
  virtual void StartReceiving(const std::string& channel) = 0;
  // The backend delivers what waits, calling Dispatch() per message and stopping as soon as
  // handler_failed(); returns how many messages it delivered.
  virtual int DeliverWaiting() = 0;
  bool handler_failed() const { return static_cast<bool>(first_error_); }
  // Hands one message to every subscription of its channel; never throws.
  void Dispatch(const std::string& channel, const void* data, int size);

 private:
  struct Subscription {
    int id;
    std::string channel;
    std::shared_ptr<const BytesHandler> handler;  // null once unsubscribed
  };
  void CountUndecodable(const std::string& channel, int64_t count_on_subscription);

  std::vector<Subscription> subscriptions_;
  std::vector<std::string> receiving_;
  int next_id_ = 1;
  std::exception_ptr first_error_;
  int64_t undecodable_messages_ = 0;
  int64_t handler_exceptions_ = 0;
};

}  // namespace slammtt
