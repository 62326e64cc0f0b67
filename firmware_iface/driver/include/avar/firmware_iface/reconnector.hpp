#pragma once
// Recovering a link whose port went away (a USB adapter unplugged, a device that reset): after an
// I/O error the link marks itself lost; each later send() asks the reconnector, which reopens the
// transport once every `every` asks (so a missing device costs a failed open only now and then)
// and says when the port is back. The send() that finds the port back redoes whatever the device
// forgot (torque on) and goes on. Used by every driver, on the thread that calls send().
// Real-time: asking is free; the reopen itself (rare, only after a failure) opens a file.

#include <atomic>
#include <cstdint>
#include <span>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/byte_transport.hpp"

namespace avar::firmware_iface {

class Reconnector {
 public:
  explicit Reconnector(std::uint32_t every = 10) noexcept : every_(every < 1 ? 1 : every) {}

  /// The transport failed with an I/O error.
  void lost() noexcept {
    lost_ = true;
    asks_ = 0;
  }
  bool is_lost() const noexcept { return lost_; }

  /// While lost: reopens the transport on every `every`-th call. Returns ok when the port is
  /// usable (never lost, or reopened now: `*reopened` is then set), io_error while it is gone.
  /// Transport: a ByteTransport or a FrameTransport (anything with reopen()).
  template <class Transport>
  Status ask(Transport& transport, bool* reopened) noexcept {
    *reopened = false;
    if (!lost_) return Status::ok;
    if (++asks_ < every_) return Status::io_error;
    asks_ = 0;
    if (transport.reopen() != Status::ok) return Status::io_error;
    lost_ = false;
    *reopened = true;
    reconnects_.fetch_add(1, std::memory_order_relaxed);
    return Status::ok;
  }

  /// Reopens that succeeded since construction. Any thread.
  std::uint64_t reconnects() const noexcept { return reconnects_.load(std::memory_order_relaxed); }
  /// A send() wrote its `bytes` (the targets' frame) to the transport. The send() thread only.
  void sent(std::size_t bytes) noexcept {
    exchanges_.fetch_add(1, std::memory_order_relaxed);
    bytes_sent_.fetch_add(bytes, std::memory_order_relaxed);
  }

  /// Counters of a write-only link (it has no replies to count): the sends that reached the
  /// transport, their bytes, and the reopens. Any thread.
  LinkCounters counters() const noexcept {
    LinkCounters k;
    k.exchanges = exchanges_.load(std::memory_order_relaxed);
    k.bytes_sent = bytes_sent_.load(std::memory_order_relaxed);
    k.reconnects = reconnects();
    return k;
  }

  /// One write through the reconnector, for links whose devices keep no state worth restoring
  /// (hobby-servo boards, DMX): reopens first while lost (as ask()), and marks the link lost on an I/O error. Real-time safe but
  /// for the reopen.
  Status write(ByteTransport& transport, std::span<const std::uint8_t> bytes) noexcept {
    bool reopened = false;
    if (ask(transport, &reopened) != Status::ok) return Status::io_error;
    const Status s = transport.write(bytes);
    if (s == Status::io_error) lost();
    if (s == Status::ok) sent(bytes.size());
    return s;
  }

 private:
  std::uint32_t every_;
  std::uint32_t asks_ = 0;
  bool lost_ = false;
  std::atomic<std::uint64_t> reconnects_{0};
  std::atomic<std::uint64_t> exchanges_{0};
  std::atomic<std::uint64_t> bytes_sent_{0};
};

}  // namespace avar::firmware_iface
