#pragma once
// Hobby servos on a PCA9685 board: `pca9685: {address, frequency, clock, outputs}` on a link
// whose port is the I2C bus (/dev/i2c-1, or sim). Each actuator is one of the board's outputs
// (`output: 0..15`) with its pulse range (`min_us`, `max_us`).

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/pca9685_link.hpp"

namespace avar::assembly {

/// The outputs and settings of pca9685 link `link` of a validated rig, on the bus described.
firmware_iface::Pca9685LinkConfig pca9685_config(const rig::Rig& rig, std::size_t link, const std::string& bus);
const Protocol& pca9685_protocol();

}  // namespace avar::assembly
