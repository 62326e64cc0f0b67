#pragma once
// A real I2C bus through Linux's i2c-dev (/dev/i2c-N; `modprobe i2c-dev`, or dtparam=i2c_arm=on
// on a Raspberry Pi). Each write is one I2C_RDWR ioctl of one message.

#include <memory>
#include <string>

#include "avar/firmware_iface/i2c_bus.hpp"

namespace avar::firmware_iface {

/// Opens `path` (/dev/i2c-1). Throws std::runtime_error naming the path and the system's reason
/// when it cannot be opened or is not an I2C adapter.
std::unique_ptr<I2cBus> open_i2c_bus(const std::string& path);

}  // namespace avar::firmware_iface
