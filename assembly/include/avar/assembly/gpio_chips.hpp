#pragma once
// The GPIO chips of a rig, each opened once by name and shared by the parts that use it: the
// gpio links' output lines and the digital inputs. A real chip is one libgpiod handle however
// many parts use it; a simulated chip is one set of lines that every part, and a test pressing
// its buttons, sees. Load-time only: open() and simulated() are not thread-safe (the chips they
// return are).

#include <map>
#include <memory>
#include <string>

#include "avar/firmware_iface/gpio_chip.hpp"
#include "avar/sim/sim_gpio_chip.hpp"

namespace avar::assembly {

class GpioChips {
 public:
  /// simulate_all: every chip is simulated whatever its name (avar play --sim).
  explicit GpioChips(bool simulate_all = false) : simulate_all_(simulate_all) {}

  /// The chip called `name`: simulated (one per name) when `simulate`, simulate_all or the name is
  /// "sim"; otherwise opened through libgpiod, once. Throws std::runtime_error naming the chip
  /// when there is no such chip (firmware_iface::open_gpio_chip).
  std::shared_ptr<firmware_iface::GpioChip> open(const std::string& name, bool simulate = false);
  /// The simulated chip called `name`, made when needed: for a test to press its buttons and
  /// read its outputs.
  sim::SimGpioChip& simulated(const std::string& name = "sim");
  /// Whether `name` opens a simulated chip.
  bool simulates(const std::string& name) const { return simulate_all_ || name == "sim"; }

 private:
  bool simulate_all_;
  std::map<std::string, std::shared_ptr<sim::SimGpioChip>> simulated_;
  std::map<std::string, std::shared_ptr<firmware_iface::GpioChip>> real_;
};

}  // namespace avar::assembly
