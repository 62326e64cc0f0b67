#pragma once
// Debouncing one digital input: a change counts once the line has stayed put for the window. The
// owner tells the debouncer each time the line may have moved (an edge, or a read that differs
// from the settled value); the window restarts from there. At the deadline the owner reads the
// line and settles: the settled value changes only to a value the line has held, untouched, for
// the whole window, so bounces and glitches shorter than it never show. Times in nanoseconds on
// one monotonic clock. Plain value type, no I/O, no clock; real-time safe.

#include <cstdint>

namespace avar::inputs {

class Debouncer {
 public:
  Debouncer(std::int64_t window_ns, bool initial) noexcept : window_ns_(window_ns), settled_(initial) {}

  /// The line may have changed at now_ns: wait for the window from here.
  void disturbed(std::int64_t now_ns) noexcept {
    pending_ = true;
    deadline_ns_ = now_ns + window_ns_;
  }
  /// Waiting for the line to stay put.
  bool pending() const noexcept { return pending_; }
  /// When to settle (meaningful while pending()).
  std::int64_t deadline_ns() const noexcept { return deadline_ns_; }
  /// Whether now_ns is at or past the deadline of a pending window.
  bool due(std::int64_t now_ns) const noexcept { return pending_ && now_ns >= deadline_ns_; }
  /// Ends a due window with the line's value read now; true when the settled value changed (a
  /// window that ends on the settled value was a bounce or a glitch).
  bool settle(bool line_value) noexcept {
    pending_ = false;
    if (line_value == settled_) return false;
    settled_ = line_value;
    return true;
  }
  bool value() const noexcept { return settled_; }
  std::int64_t window_ns() const noexcept { return window_ns_; }

 private:
  std::int64_t window_ns_;
  std::int64_t deadline_ns_ = 0;
  bool settled_;
  bool pending_ = false;
};

}  // namespace avar::inputs
