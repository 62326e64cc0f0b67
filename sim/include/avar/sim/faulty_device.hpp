#pragma once
// Fault injection between a host and a simulated device: wraps any ByteDevice and, by a seeded
// plan, loses commands, loses, corrupts, truncates, duplicates, reorders or delays replies, makes
// the device stop answering altogether, or makes it answer garbage. Works under every host (the
// in-memory SimWire, a pseudo-terminal), so a driver's handling of each fault is tested on the
// same bytes it meets on a real bus. A "reply chunk" is what the device has queued when the host
// collects replies: one or more packets. Not thread-safe, like every ByteDevice.

#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "avar/sim/byte_device.hpp"

namespace avar::sim {

struct FaultPlan {
  double drop_command = 0;     ///< probability that a chunk of host bytes never reaches the device
  double drop_reply = 0;       ///< probability that a reply chunk is lost
  double corrupt_reply = 0;    ///< probability that one byte of a reply chunk is flipped
  double duplicate_reply = 0;  ///< probability that a reply chunk arrives twice
  double truncate_reply = 0;   ///< probability that a reply chunk loses its tail (at least one byte)
  double reorder_reply = 0;    ///< probability that a reply chunk arrives after the next one
  double delay_reply_s = 0;    ///< every reply is held back this long (simulated seconds)
  bool silent = false;         ///< the device takes commands but never answers
  /// The device answers noise: every reply chunk becomes random bytes of its length, and random
  /// bytes arrive unasked (kGarbageBytesPerSecond) whether or not the host asked anything.
  bool garbage = false;
  std::uint64_t seed = 1;
};

/// What the injector did, for tests to compare with what the driver counted.
struct FaultCounts {
  std::uint64_t commands_dropped = 0;
  std::uint64_t replies_dropped = 0;
  std::uint64_t replies_corrupted = 0;
  std::uint64_t replies_duplicated = 0;
  std::uint64_t replies_silenced = 0;
  std::uint64_t replies_truncated = 0;
  std::uint64_t replies_reordered = 0;
  std::uint64_t replies_garbled = 0;
  std::uint64_t garbage_bytes = 0;  ///< random bytes sent, unasked or in place of replies
};

class FaultyDevice final : public ByteDevice {
 public:
  /// Rate of unasked noise while FaultPlan::garbage holds (a byte a millisecond: a line that
  /// picks up interference, or a device at the wrong baud rate).
  static constexpr double kGarbageBytesPerSecond = 1000;

  /// inner is borrowed and must outlive this.
  FaultyDevice(ByteDevice& inner, FaultPlan plan);

  /// Changes the plan from now on (a device that goes silent mid-show, then comes back).
  void set_plan(const FaultPlan& plan);
  const FaultCounts& counts() const { return counts_; }

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  void advance(double dt_s) override;
  /// Bytes that reached this side of the wire, dropped ones included (what a host waits on).
  std::uint64_t bytes_received() const override { return bytes_received_; }

 private:
  struct Held {
    double release_s;
    std::vector<std::uint8_t> bytes;
  };
  bool chance(double p);
  /// Moves the inner device's queued replies through the plan into held_.
  void collect();
  /// Queues a reply chunk for release after the plan's delay (twice when duplicated).
  void hold(std::vector<std::uint8_t> chunk);
  std::uint8_t random_byte();

  ByteDevice& inner_;
  FaultPlan plan_;
  std::mt19937_64 random_;
  FaultCounts counts_;
  double now_s_ = 0;
  std::uint64_t bytes_received_ = 0;
  std::deque<Held> held_;           ///< replies on their way, oldest first
  std::deque<std::uint8_t> ready_;  ///< released reply bytes
  std::vector<std::uint8_t> parked_;  ///< a reordered chunk, waiting for the next one to pass it
  double garbage_owed_ = 0;           ///< fractional unasked garbage bytes carried between advances
};

}  // namespace avar::sim
