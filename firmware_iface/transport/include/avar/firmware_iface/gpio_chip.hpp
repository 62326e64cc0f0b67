#pragma once
// The GPIO seam: one chip of lines (gpiochip0 on a Raspberry Pi header), whose lines are
// requested as inputs (with active-low and bias, optionally with edge events) or as outputs
// (with an initial value), then read, set and waited on. Values are logical: with active_low a
// line reads 1 while it is low, and setting 1 drives it low. open_gpio_chip() (libgpiod_chip.hpp,
// avar::transport_gpio) opens a real chip; avar::sim::SimGpioChip is the simulated one.
//
// Threads: request and release lines on one thread before others use them. Afterwards get() and
// set() on output lines (the loop, or a link's I/O thread) and wait_edges() with get() on input
// lines (an input thread) may run on different threads at the same time.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

/// The bias a line's input asks for (kernel 5.5 or later; as_is leaves the line's setting).
enum class GpioBias { as_is, disabled, pull_up, pull_down };

/// "as_is", "disabled", "pull_up", "pull_down".
const char* to_string(GpioBias b) noexcept;

struct GpioInputRequest {
  unsigned line = 0;
  bool active_low = false;
  GpioBias bias = GpioBias::as_is;
  bool edge_events = true;  ///< deliver both edges to wait_edges()
};

struct GpioOutputRequest {
  unsigned line = 0;
  bool active_low = false;
  bool initial = false;  ///< logical value driven from the request on
};

/// An edge seen on an input line requested with edge_events.
struct GpioEdge {
  unsigned line = 0;
  bool rising = false;       ///< the line's logical value became 1
  std::int64_t time_ns = 0;  ///< when it happened, as the chip stamps it
};

class GpioChip {
 public:
  virtual ~GpioChip() = default;

  /// For messages: "GPIO chip 'gpiochip0' (pinctrl-bcm2711)", "simulated GPIO chip 'sim'".
  virtual const std::string& describe() const noexcept = 0;
  /// Lines on the chip, numbered 0 to line_count() - 1.
  virtual unsigned line_count() const noexcept = 0;

  /// Requests a line as an input for avar. Throws std::runtime_error naming the chip and the
  /// line when it does not exist, is in use, or the request fails. Not real-time.
  virtual void request_input(const GpioInputRequest& request) = 0;
  /// Requests a line as an output, driven to request.initial at once. Throws like
  /// request_input(). Not real-time.
  virtual void request_output(const GpioOutputRequest& request) = 0;
  /// Gives a requested line back (an output stops being driven). Unknown lines are ignored.
  virtual void release(unsigned line) noexcept = 0;

  /// The logical value of a requested line (an output reads what it drives). Real-time safe
  /// (one ioctl); Status::out_of_range for a line not requested, io_error when the read fails.
  virtual Status get(unsigned line, bool& value) noexcept = 0;
  /// Drives a requested output line to a logical value. Real-time safe (one ioctl);
  /// Status::out_of_range for a line not requested as an output.
  virtual Status set(unsigned line, bool value) noexcept = 0;

  /// Waits up to `timeout` for edges on the input lines requested with edge_events and moves up
  /// to out.size() of them, oldest first, into `out`; `count` says how many (0 on timeout).
  /// Status::io_error when waiting or reading fails. Blocks: call from an input thread.
  virtual Status wait_edges(std::chrono::nanoseconds timeout, std::span<GpioEdge> out, std::size_t& count) noexcept = 0;
};

}  // namespace avar::firmware_iface
