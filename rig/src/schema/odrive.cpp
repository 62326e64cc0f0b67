// ODrive axes (CAN Simple, firmware 0.5.x) on a CAN link: `current_limit`, `input_mode`.
#include <array>

#include "avar/firmware_iface/odrive_can_codec.hpp"
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

constexpr std::array<std::string_view, 2> kOdriveKeys{"current_limit", "input_mode"};

ActuatorOptions parse_odrive(const LinkSettings& s, int, const SourceLocation&) {
  OdriveOptions o;
  if (const ScalarValue* m = s.find("input_mode")) {
    const std::string mode = m->as_string("input_mode");
    if (mode == "passthrough") o.input_mode = OdriveInputMode::passthrough;
    else if (mode == "pos_filter") o.input_mode = OdriveInputMode::pos_filter;
    else if (mode == "trap_traj") o.input_mode = OdriveInputMode::trap_traj;
    else m->fail("unknown ODrive input_mode " + m->describe() + "; expected one of: passthrough, pos_filter, trap_traj");
  }
  if (const ScalarValue* c = s.find("current_limit")) o.current_limit = number_in(*c, "current_limit", 0.1, 200, "A");
  return o;
}

}  // namespace

const CanDriveSchema& odrive_schema() {
  static const CanDriveSchema p{
      "odrive",
      "ODrive",
      0,
      firmware_iface::odrive::kMaxNode,
      "turns",
      "125000, 250000, 500000, 1000000",
      [](int bitrate) { return bitrate == 125'000 || bitrate == 250'000 || bitrate == 500'000 || bitrate == 1'000'000; },
      [] { return std::span<const std::string_view>(kOdriveKeys); },
      parse_odrive,
      [](const ActuatorSpec&) { return 1.0; },
      [](const ActuatorSpec&) {},
      [](const ActuatorSpec& a, const CanOptions&, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({node << 5, (node << 5) | 0x1F, false});
      },
  };
  return p;
}

}  // namespace avar::rig
