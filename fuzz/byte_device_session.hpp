#pragma once
// Drives a simulated serial device (sim::ByteDevice) the way its host does, from fuzz bytes:
// each step is one selector byte then its argument. Selector % 4: 0 a chunk of up to 64 request
// bytes (length byte, then the bytes), 1 advance simulated time by (byte / 1000) s, 2 take the
// replies, 3 a single byte. The device must take any bytes without crashing and never answer
// more than its outbox holds. Simulated time stops at max_seconds (kMaxSessionSeconds unless the
// target says less): a device integrates its servos in 1 ms steps, and minutes of simulated time
// per input only made the fuzzer slow (an SSC-32's 32 channels over 8 KB of advances took more
// than the 2 s hang limit).

#include <array>
#include <cstdint>
#include <cstdlib>

#include "avar/sim/byte_device.hpp"
#include "fuzz_bytes.hpp"

namespace avar::fuzz {

inline constexpr double kMaxSessionSeconds = 30;

inline void run_byte_device_session(sim::ByteDevice& device, ByteReader& in, double max_seconds = kMaxSessionSeconds) {
  std::array<std::uint8_t, 256> replies{};
  std::uint64_t fed = 0;
  double simulated_s = 0;
  while (!in.empty()) {
    const std::uint8_t op = in.u8();
    switch (op % 4) {
      case 0: {
        const auto chunk = in.take(in.u8() % 65);
        device.receive(chunk);
        fed += chunk.size();
        break;
      }
      case 1: {
        const double dt = in.u8() / 1000.0;
        if (simulated_s + dt <= max_seconds) device.advance(dt);
        simulated_s += dt;
        break;
      }
      case 2:
        while (device.take_replies(replies) == replies.size()) {
        }
        break;
      default: {
        const auto one = in.take(1);
        device.receive(one);
        fed += one.size();
      }
    }
  }
  if (device.bytes_received() != fed) std::abort();
  while (device.take_replies(replies) == replies.size()) {
  }
}

}  // namespace avar::fuzz
