#pragma once
// The latest value of every named control, written by input devices' threads and read by the
// control loop: one slot per control, each a few atomics, so a writer never waits for the loop
// and the loop never waits for a writer (a reader may see a value one message newer than the
// sequence number it read with it: harmless, the next tick reads both again).

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "avar/inputs/input_source.hpp"

namespace avar::control {

/// What the loop reads of one control.
struct ControlReading {
  double value = 0;
  bool bipolar = false;
  std::uint64_t sequence = 0;   ///< messages so far; 0: never moved
  std::int64_t arrived_ns = 0;  ///< CLOCK_MONOTONIC of the newest message
};

class ControlMailbox final : public inputs::ControlSink {
 public:
  /// One slot per name (duplicates are one slot). Allocates.
  explicit ControlMailbox(std::vector<std::string> names);

  /// From any thread: a control with a slot takes the value; any other name is counted as
  /// unknown. Lock-free; the name lookup hashes, so it is for input threads, not the tick.
  void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept override;

  /// From any thread; real-time safe.
  ControlReading read(std::size_t control) const noexcept;
  std::size_t size() const noexcept { return names_.size(); }
  const std::string& name(std::size_t control) const noexcept { return names_[control]; }
  /// Slot of `name`, or size().
  std::size_t find(std::string_view name) const noexcept;
  /// Messages for controls with no slot (nothing maps them).
  std::uint64_t unknown() const noexcept { return unknown_.load(std::memory_order_relaxed); }

 private:
  struct Slot {
    std::atomic<double> value{0};
    std::atomic<bool> bipolar{false};
    std::atomic<std::int64_t> arrived_ns{0};
    std::atomic<std::uint64_t> sequence{0};
  };
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>{}(s); }
  };
  std::vector<std::string> names_;
  std::unordered_map<std::string, std::size_t, NameHash, std::equal_to<>> index_;
  std::unique_ptr<Slot[]> slots_;
  std::atomic<std::uint64_t> unknown_{0};
};

}  // namespace avar::control
