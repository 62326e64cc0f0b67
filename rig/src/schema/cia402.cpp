// CANopen CiA 402 servo drives (cyclic synchronous position) on a CAN link: `counts_per_turn`.
#include <array>
#include <cmath>

#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

constexpr std::array<std::string_view, 1> kCia402Keys{"counts_per_turn"};

ActuatorOptions parse_cia402(const LinkSettings& s, int node, const SourceLocation& where) {
  const ScalarValue* c = s.find("counts_per_turn");
  if (!c)
    ScalarValue{"", false, "nothing", where}.fail(
        "expected counts_per_turn for the CiA 402 drive at node " + std::to_string(node) +
        ": the position counts of one motor turn in the drive's user units (its encoder resolution, such as 131072 for 17 bits)");
  return Cia402Options{static_cast<double>(integer_in(*c, "counts_per_turn", 1, 1LL << 30)), c->where};
}

}  // namespace

const CanDriveSchema& cia402_schema() {
  static const CanDriveSchema p{
      "cia402",
      "CiA 402 drive",
      1,
      127,
      "counts",
      "any CANopen rate; 500000 and 1000000 are usual",
      [](int) { return true; },
      [] { return std::span<const std::string_view>(kCia402Keys); },
      parse_cia402,
      [](const ActuatorSpec& a) { return a.options_as<Cia402Options>().counts_per_turn; },
      [](const ActuatorSpec& a) {
        // Targets are 32-bit counts.
        if (std::max(std::abs(a.calibration.device_low()), std::abs(a.calibration.device_high())) > 2147483647.0)
          throw InputError(a.options_as<Cia402Options>().counts_where,
                           "the channel's range takes this drive beyond the 32-bit position range (±2147483647 counts); expected "
                           "fewer counts_per_turn or a smaller gear_ratio");
      },
      [](const ActuatorSpec& a, const CanOptions&, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({0x000, 0x000, true});  // NMT, from the host to every node
        out.push_back({0x080, 0x080, true});  // SYNC
        for (std::uint32_t base :
             {0x080u, 0x180u, 0x200u, 0x280u, 0x300u, 0x380u, 0x400u, 0x480u, 0x500u, 0x580u, 0x600u, 0x700u})
          out.push_back({base + node, base + node, false});
      },
  };
  return p;
}

}  // namespace avar::rig
