#pragma once
// The seam between a simulated CAN device (a drive, a motor) and the simulated bus that carries
// its frames (SimCanBus, which serves the in-memory transport and the simulated SLCAN adapter).
// A node decodes exactly what the real device accepts and answers as it does, error replies
// included; it never sees its own frames. Not thread-safe: its bus serialises every call.

#include <cstdint>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::sim {

class CanNode {
 public:
  virtual ~CanNode() = default;
  /// A frame another node (or the host) put on the bus. Nodes filter by id themselves.
  virtual void receive(const firmware_iface::CanFrame& frame) = 0;
  /// The oldest frame this node waits to send, or false when it has none. The bus arbitrates
  /// between nodes by these frames' ids (lowest wins) and calls pop_transmit() for the winner.
  virtual bool peek_transmit(firmware_iface::CanFrame* frame) const = 0;
  virtual void pop_transmit() = 0;
  /// Advances the node's simulated time by dt_s seconds (motion, cyclic messages, timeouts).
  virtual void advance(double dt_s) = 0;
};

}  // namespace avar::sim
