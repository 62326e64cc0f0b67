#pragma once
// Sends prepared OSC messages from a thread of its own, on request from the real-time loop: the
// loop calls fire(i) (lock-free, allocation-free: the index goes into a single-producer ring) and
// the thread sends message i over UDP (liblo). The messages and their destinations are built once,
// at construction.
//
// Threads: fire() from one producer thread (the loop); everything else from the owner's thread.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace avar::firmware_iface {

struct OscArgument {
  char type = 'f';  ///< 'f' float, 'i' 32-bit integer, 's' string
  double number = 0;
  std::string text;
};

struct OscCueMessage {
  std::string host;  ///< numeric IPv4
  int port = 0;
  std::string address;  ///< "/path"
  std::vector<OscArgument> arguments;
};

class OscCueSender {
 public:
  /// Prepares every message and starts the thread. Throws std::invalid_argument for an argument
  /// type other than f, i, s.
  explicit OscCueSender(const std::vector<OscCueMessage>& messages);
  /// Sends what was fired and not yet sent, then stops the thread.
  ~OscCueSender();
  OscCueSender(const OscCueSender&) = delete;
  OscCueSender& operator=(const OscCueSender&) = delete;

  /// Asks the thread to send message `index`. Real-time safe: no allocation, no lock, no system
  /// call but a futex wake. false (and counted as dropped) when the ring is full.
  bool fire(std::size_t index) noexcept;

  /// Waits until everything fired so far was sent (or failed). Not real-time.
  void flush();

  /// Counters, any thread.
  std::uint64_t sent() const noexcept { return sent_.load(std::memory_order_relaxed); }
  std::uint64_t failed() const noexcept { return failed_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  void run();

  struct Prepared;
  std::vector<std::unique_ptr<Prepared>> prepared_;
  std::vector<std::uint32_t> ring_;
  std::uint32_t mask_ = 0;
  std::atomic<std::uint32_t> head_{0};  ///< next to send (consumer)
  std::atomic<std::uint32_t> tail_{0};  ///< next free (producer)
  std::atomic<std::uint32_t> wake_{0};  ///< bumped on every fire and on stop
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> failed_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::thread thread_;
};

}  // namespace avar::firmware_iface
