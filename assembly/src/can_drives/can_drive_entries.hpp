#pragma once
// The registry entries of the CAN drive protocols, one file each.

#include "avar/assembly/can_drive.hpp"

namespace avar::assembly {

const CanDriveProtocol& odrive_drive();
const CanDriveProtocol& cia402_drive();
const CanDriveProtocol& mit_drive();

}  // namespace avar::assembly
