#pragma once
// Drives a simulated CAN device (sim::CanNode) the way its bus does, from fuzz bytes: each step
// is a selector byte; selector % 3: 0 a frame for the node (can_frame_input.hpp), 1 advance
// simulated time by (byte / 1000) s (up to kMaxSessionSeconds in all, as byte_device_session.hpp),
// 2 drain what the node waits to send.

#include "avar/sim/can_node.hpp"
#include "byte_device_session.hpp"
#include "can_frame_input.hpp"

namespace avar::fuzz {

inline void drain_can_node(sim::CanNode& node) {
  firmware_iface::CanFrame out;
  // A node sends a bounded backlog: more than this many frames at once would be a runaway.
  for (int i = 0; i < 4096 && node.peek_transmit(&out); ++i) node.pop_transmit();
}

inline void run_can_node_session(sim::CanNode& node, ByteReader& in) {
  double simulated_s = 0;
  while (!in.empty()) {
    switch (in.u8() % 3) {
      case 0: node.receive(read_can_frame(in)); break;
      case 1: {
        const double dt = in.u8() / 1000.0;
        if (simulated_s + dt <= kMaxSessionSeconds) node.advance(dt);
        simulated_s += dt;
        break;
      }
      default: drain_can_node(node);
    }
  }
  drain_can_node(node);
}

}  // namespace avar::fuzz
