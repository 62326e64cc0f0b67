#include "avar/control/rig.hpp"

namespace avar::control {

const char* to_string(Failsafe f) noexcept {
  switch (f) {
    case Failsafe::hold: return "hold";
    case Failsafe::rest: return "rest";
    case Failsafe::release: return "release";
  }
  return "unknown";
}

const char* to_string(Protocol p) noexcept {
  switch (p) {
    case Protocol::maestro: return "maestro";
    case Protocol::dynamixel: return "dynamixel";
    case Protocol::feetech: return "feetech";
    case Protocol::ssc32: return "ssc32";
    case Protocol::dmx: return "dmx";
  }
  return "unknown";
}

std::optional<std::size_t> Rig::find_channel(std::string_view wanted) const {
  for (std::size_t i = 0; i < channels.size(); ++i)
    if (channels[i].name == wanted) return i;
  return std::nullopt;
}

std::optional<std::size_t> Rig::find_link(std::string_view wanted) const {
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == wanted) return i;
  return std::nullopt;
}

std::vector<double> Rig::rest_frame() const {
  std::vector<double> frame;
  frame.reserve(channels.size());
  for (const ChannelSpec& c : channels) frame.push_back(c.rest);
  return frame;
}

std::string Rig::channel_names() const {
  std::string out;
  for (const ChannelSpec& c : channels) out += (out.empty() ? "" : ", ") + c.name;
  return out;
}

}  // namespace avar::control
