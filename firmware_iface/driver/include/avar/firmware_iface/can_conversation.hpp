#pragma once
// Blocking request/answer on a CAN bus, for bringing drives up (start, read_positions): send a
// frame, then wait on the transport's clock for the one frame that answers it. Frames that do
// not answer are dropped; a bus-off error frame ends the wait with io_error. Not real-time.

#include <chrono>
#include <span>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/frame_transport.hpp"

namespace avar::firmware_iface {

/// Waits up to `timeout` for a frame with match(frame) true; copies it into *answer (may be
/// null). ok, timeout, or io_error.
template <class Match>
Status await_frame(FrameTransport& bus, std::chrono::nanoseconds timeout, Match&& match, CanFrame* answer = nullptr) {
  const std::chrono::nanoseconds deadline = bus.now() + timeout;
  CanFrame f;
  for (;;) {
    const Status s = bus.receive(&f, deadline);
    if (s != Status::ok) return s;
    if (f.error) {
      if (f.id & kCanErrorBusOff) return Status::io_error;
      continue;
    }
    if (match(f)) {
      if (answer) *answer = f;
      return Status::ok;
    }
  }
}

/// Sends `request`, then await_frame().
template <class Match>
Status ask_frame(FrameTransport& bus, const CanFrame& request, std::chrono::nanoseconds timeout, Match&& match,
                 CanFrame* answer = nullptr) {
  if (const Status s = bus.send(std::span<const CanFrame>(&request, 1)); s != Status::ok) return s;
  return await_frame(bus, timeout, match, answer);
}

}  // namespace avar::firmware_iface
