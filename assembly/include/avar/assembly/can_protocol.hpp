#pragma once
// The `can` link protocol: a CAN bus reached through an SLCAN adapter (a serial port such as
// /dev/ttyACM0), a SocketCAN interface (can0) or a simulated bus, carrying ODrive, CiA 402 and
// MIT-style drives (the CAN drive registry, can_drive.hpp).

#include "avar/assembly/can_drive.hpp"
#include "avar/assembly/protocol.hpp"

namespace avar::assembly {

const Protocol& can_protocol();

/// `avar sim can` and `avar sim DRIVE`: a simulated SLCAN adapter with drives of `drive` at the
/// node ids of option `ids`, on a bus at option `bitrate`. Throws SimOptionError naming the option.
ServedDevice standalone_slcan(const CanDriveProtocol& drive, const SimValues& values);
/// The offer of a drive protocol: its drives alone behind a simulated SLCAN adapter (`make` is
/// left for the entry to set: it names its drive).
SimOffer drive_sim_offer(const char* name, const char* summary, const char* example);

}  // namespace avar::assembly
