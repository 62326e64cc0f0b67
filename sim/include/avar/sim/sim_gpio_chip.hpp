#pragma once
// A simulated GPIO chip: the GPIO seam (firmware_iface::GpioChip) in memory, with the other
// side of its lines open to tests and other threads, as switches and meters wired to a real
// chip would be. An input line reads the level put on it from outside (set_level), or its bias
// when nothing was (pull-up: high, otherwise low); an output line's level is what the chip
// drives. Active-low lines invert between level and logical value, as libgpiod does. Every
// change of an input's logical value on a line requested with edge events is queued for
// wait_edges() (at most kEdgeQueue; the oldest are dropped beyond, as the kernel's FIFO does).
//
// Thread-safe: every member may be called from any thread (one mutex; wait_edges() waits on a
// condition variable and never holds the mutex while waiting).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "avar/firmware_iface/gpio_chip.hpp"

namespace avar::sim {

class SimGpioChip final : public firmware_iface::GpioChip {
 public:
  static constexpr std::size_t kEdgeQueue = 256;

  /// A chip of `lines` lines (a Raspberry Pi's gpiochip0 has 54 to 58), called `name` in
  /// messages.
  explicit SimGpioChip(const std::string& name = "sim", unsigned lines = 64);

  const std::string& describe() const noexcept override { return describe_; }
  unsigned line_count() const noexcept override { return static_cast<unsigned>(lines_.size()); }
  /// Throw std::runtime_error naming the chip and the line for a line that does not exist or is
  /// already requested.
  void request_input(const firmware_iface::GpioInputRequest& request) override;
  void request_output(const firmware_iface::GpioOutputRequest& request) override;
  void release(unsigned line) noexcept override;
  Status get(unsigned line, bool& value) noexcept override;
  Status set(unsigned line, bool value) noexcept override;
  /// Edges are stamped with CLOCK_MONOTONIC at set_level().
  Status wait_edges(std::chrono::nanoseconds timeout, std::span<firmware_iface::GpioEdge> out,
                    std::size_t& count) noexcept override;

  // The outside of the lines.

  /// Puts a level on a line from outside (a switch closing to ground: false). On an output line
  /// it is ignored (the chip drives it). Throws std::out_of_range for a line that does not exist.
  void set_level(unsigned line, bool high);
  /// Lets go of a line from outside: it reads its bias again.
  void float_line(unsigned line);
  /// The line's level: what an output drives, else the outside level or the bias.
  bool level(unsigned line) const;
  /// Level changes an output line has made since it was requested.
  std::uint64_t output_changes(unsigned line) const;
  bool is_output(unsigned line) const;
  bool is_requested(unsigned line) const;
  /// Edges dropped because nobody took them in time.
  std::uint64_t edges_dropped() const;

 private:
  struct Line {
    bool requested = false;
    bool output = false;
    bool active_low = false;
    firmware_iface::GpioBias bias = firmware_iface::GpioBias::as_is;
    bool edge_events = false;
    bool driven = false;          ///< output: the level driven
    std::optional<bool> outside;  ///< input: a level put on it from outside
    std::uint64_t output_changes = 0;
  };

  Line& checked(unsigned line, const char* what);
  bool level_of(const Line& l) const noexcept;
  /// After an outside change: queues an edge when the logical value moved.
  void note_edge(unsigned line, bool before) noexcept;

  std::string describe_;
  mutable std::mutex mutex_;
  std::condition_variable edge_ready_;
  std::vector<Line> lines_;
  std::deque<firmware_iface::GpioEdge> edges_;
  std::uint64_t edges_dropped_ = 0;
};

}  // namespace avar::sim
