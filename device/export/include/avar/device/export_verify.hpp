#pragma once
// avar export --verify: the exported project, as written, built for the host and for its target,
// run under the target's emulator (simavr for the AVRs, qemu-system-arm for the Cortex-M boards),
// and every control tick's I2C bytes and 16-bit outputs compared with the host build's. The
// engine's source is the same on both sides: a mismatch is a compiler's or a target's difference.

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "avar/device/project_export.hpp"

namespace avar::device {

/// How a target is built and emulated.
struct EmulatedTarget {
  std::string compiler;                    ///< avr-g++ or arm-none-eabi-g++
  std::vector<std::string> flags;          ///< -mmcu=..., -mcpu=...
  std::string emulator;                    ///< simavr or qemu-system-arm
  std::vector<std::string> emulator_args;  ///< before the ELF (simavr) or around it (QEMU)
  bool avr = false;
};

/// The emulation of `target`, or nothing for a target no emulator here runs (esp32c3).
const EmulatedTarget* emulation_of(const DeviceTarget& target);

struct ExportVerification {
  std::size_t samples = 0;     ///< channel outputs compared (control ticks times channels)
  std::size_t mismatches = 0;  ///< samples in a second whose hash differs from the host's
  std::size_t ticks = 0;
  double emulator_seconds = 0;
  std::string emulator;                ///< what ran the target's build
  std::vector<std::string> differing;  ///< the first differing lines, host then target
  std::size_t flash_bytes = 0;         ///< the target build's program size (text and data)
  std::size_t ram_bytes = 0;           ///< its static RAM (data and bss)
};

/// Builds and runs the project written in `project_dir` (write_project) on the host and under its
/// target's emulator, in a temporary directory; progress lines on `progress`. Throws
/// std::runtime_error naming what is missing (a compiler, an emulator: scripts/install-deps.sh
/// installs them) or what failed (a build's errors, a run that did not finish).
ExportVerification verify_export(const Project& project, const std::filesystem::path& project_dir, std::ostream& progress);

}  // namespace avar::device
