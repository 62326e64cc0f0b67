#pragma once
// Feeds a byte stream to a BusCodec the way BusExchange does: parse what has arrived; on
// need_more add *want bytes; otherwise drop *used bytes and go on. Aborts when the codec breaks
// its contract: *used beyond the bytes it was given, no progress on a verdict, a want of 0, a
// reply whose parameters lie outside the codec's scratch or the input.

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "avar/firmware_iface/bus_codec.hpp"

namespace avar::fuzz {

inline void run_bus_stream(firmware_iface::BusCodec& codec, std::span<const std::uint8_t> stream) {
  using firmware_iface::Framing;
  std::vector<std::uint8_t> rx;
  std::size_t next = 0;
  for (;;) {
    firmware_iface::BusReply reply;
    std::size_t used = 0, want = 1;
    const Framing f = codec.parse(rx, &reply, &used, &want);
    if (f == Framing::need_more) {
      if (want == 0) std::abort();
      if (next == stream.size()) return;
      const std::size_t n = std::min(want, stream.size() - next);
      rx.insert(rx.end(), stream.begin() + static_cast<std::ptrdiff_t>(next),
                stream.begin() + static_cast<std::ptrdiff_t>(next + n));
      next += n;
      continue;
    }
    if (used == 0 || used > rx.size()) std::abort();
    if (f == Framing::reply) {
      // Touch every parameter byte: ASan reports a span that points past what it may read.
      unsigned sum = reply.error;
      for (std::uint8_t b : reply.params) sum += b;
      if (sum == 0xFFFF'FFFFu) std::abort();
    }
    rx.erase(rx.begin(), rx.begin() + static_cast<std::ptrdiff_t>(used));
  }
}

}  // namespace avar::fuzz
