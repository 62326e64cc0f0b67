#pragma once
// The request/response engine under every polled bus (smart servos today; CAN drives and SLCAN
// plug in with their own BusCodec and transport). Per exchange (one driver send()): begin()
// (which reopens a lost port now and then), the driver's writes, collect() of the replies with
// one deadline on the transport's clock, retry() of the devices whose reply was lost or corrupt
// (bounded per exchange), then settle(): stale feedback becomes absent and each device's silence
// is judged by its DeviceWatch (device_watch.hpp): a device lost makes the exchange a timeout (the
// watchdog fault).
// One set of LinkCounters for all of it.
//
// Devices are addressed by slot: the driver's actuator index (an ActuatorTable index).
// Threads: one thread (the link's I/O thread) drives the exchange; counters() from any thread.
// Real-time: everything but the constructor allocates nothing and throws nothing; collect()
// waits for replies, bounded by the reply timeout.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/atomic_link_counters.hpp"
#include "avar/firmware_iface/bus_codec.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/reconnector.hpp"

namespace avar::firmware_iface {

struct BusExchangeConfig {
  /// Longest collect() waits for its replies, on the transport's clock. Replies that have
  /// already arrived are still taken after it (reads of 0 ms), never more bytes than the
  /// replies asked for.
  std::chrono::milliseconds reply_timeout{10};
  /// Retries per exchange, each a request to one device whose reply was lost or corrupt.
  std::uint32_t retries = 1;
  /// A device's silence budget (DeviceWatch): silent exchanges in a row that make settle()
  /// report a timeout (0 is taken as 1).
  std::uint32_t silent_exchanges = 10;
  /// While the port is gone, begin() reopens it every this many exchanges.
  std::uint32_t reconnect_every = 10;
  /// Largest reply (and retry request) in bytes.
  std::size_t max_packet = 1024;
};

/// Takes a reply of the device in `slot`; returns false when it is not the reply asked for
/// (wrong length: a stray that is skipped). A non-owning reference to a callable.
class ReplySink {
 public:
  template <class F>
  ReplySink(F& f) noexcept  // implicit: drivers pass their lambdas as they are
      : object_(&f),
        call_([](void* o, std::size_t slot, const BusReply& r) noexcept { return (*static_cast<F*>(o))(slot, r); }) {}
  bool operator()(std::size_t slot, const BusReply& r) const noexcept { return call_(object_, slot, r); }

 private:
  void* object_;
  bool (*call_)(void*, std::size_t, const BusReply&) noexcept;
};

class BusExchange {
 public:
  /// devices[slot]: the bus address of each slot. The transport and codec are borrowed.
  BusExchange(ByteTransport& transport, BusCodec& codec, std::vector<std::uint32_t> devices, BusExchangeConfig config);

  /// Starts an exchange: forgets which devices answered and, while the port is lost, reopens it
  /// every reconnect_every calls (io_error until it is back; *reopened when it came back now,
  /// so that the driver restores what the devices forgot). Counts the exchange.
  Status begin(bool* reopened) noexcept;
  /// Drops stale input, then writes; counts the bytes. An I/O error marks the port lost.
  Status write(std::span<const std::uint8_t> bytes) noexcept;
  /// Waits for one reply from each of `slots` (in any order) until all came or the deadline
  /// (now + reply_timeout) passed, handing each to `take`. reply_size: the bytes one reply
  /// takes, read in one go (0: as the codec asks). Returns ok, timeout (someone's reply missing
  /// or corrupt, each counted as a timeout) or io_error.
  Status collect(std::span<const std::size_t> slots, std::size_t reply_size, ReplySink take) noexcept;
  /// write(request), then collect() of the one reply of `slot`.
  Status query(std::size_t slot, std::span<const std::uint8_t> request, std::size_t reply_size, ReplySink take) noexcept;
  /// For the slots in `asked` that have not answered in this exchange, at most `retries` in
  /// all: asks each again (the codec's encode_retry) and collects its reply. io_error or ok.
  Status retry(std::span<const std::size_t> asked, std::size_t reply_size, ReplySink take) noexcept;
  /// Ends the exchange's feedback: every slot that is not in `asked` or did not answer its last
  /// collect() has its feedback forgotten in `table` (absent, not old); the silence of each
  /// slot in `asked` is counted by its DeviceWatch (an answer resets it). Returns timeout while
  /// one of them is lost (silent for silent_exchanges exchanges in a row).
  Status settle(std::span<const std::size_t> asked, ActuatorTable& table) noexcept;

  /// The slot answered its last collect() of this exchange.
  bool answered(std::size_t slot) const noexcept { return answered_[slot]; }
  void set_reply_timeout(std::chrono::milliseconds timeout) noexcept { config_.reply_timeout = timeout; }
  /// Bytes written and read since begin().
  std::size_t exchange_bytes() const noexcept { return exchange_bytes_; }
  /// Any thread.
  LinkCounters counters() const noexcept;

 private:
  ByteTransport& transport_;
  BusCodec& codec_;
  std::vector<std::uint32_t> devices_;
  BusExchangeConfig config_;
  Reconnector reconnector_;
  std::unique_ptr<bool[]> answered_;  ///< per slot, this exchange
  std::unique_ptr<bool[]> awaited_;   ///< per slot, this collect()
  std::vector<DeviceWatch> watches_;  ///< per slot: its silence
  std::vector<std::uint8_t> rx_;
  std::vector<std::uint8_t> request_;
  std::size_t exchange_bytes_ = 0;
  AtomicLinkCounters counters_;
};

}  // namespace avar::firmware_iface
