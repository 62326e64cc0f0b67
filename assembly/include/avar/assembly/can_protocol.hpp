#pragma once
// The `can` link protocol: a CAN bus reached through an SLCAN adapter (a serial port such as
// /dev/ttyACM0), a SocketCAN interface (can0) or a simulated bus, carrying ODrive, CiA 402 and
// MIT-style drives (the CAN drive registry, can_drive.hpp).

#include "avar/assembly/protocol.hpp"

namespace avar::assembly {

const Protocol& can_protocol();

}  // namespace avar::assembly
