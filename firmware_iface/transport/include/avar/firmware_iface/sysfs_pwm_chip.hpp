#pragma once
// A real PWM chip through Linux's sysfs PWM class (/sys/class/pwm/pwmchipN; on a Raspberry Pi,
// dtoverlay=pwm-2chan gives pwmchip0 with outputs 0 and 1 on GPIO 18 and 19). An output is
// exported (echo N > export) if it is not already, its period and polarity set once; each pulse
// is one write to its duty_cycle file, kept open.

#include <memory>
#include <string>

#include "avar/firmware_iface/pwm_chip.hpp"

namespace avar::firmware_iface {

/// Opens `port`: a chip's directory (/sys/class/pwm/pwmchip0), its name (pwmchip0) or its
/// number (0), the last two under `sysfs_root`. Throws std::runtime_error naming the chip and the
/// system's reason when it is absent or not a PWM chip.
std::unique_ptr<PwmChip> open_pwm_chip(const std::string& port, const std::string& sysfs_root = "/sys/class/pwm");

}  // namespace avar::firmware_iface
