#include "avar/rig/rig.hpp"

namespace avar::rig {

const char* to_string(Failsafe f) noexcept {
  switch (f) {
    case Failsafe::hold: return "hold";
    case Failsafe::rest: return "rest";
    case Failsafe::release: return "release";
  }
  return "unknown";
}

const char* to_string(ChannelKind k) noexcept {
  switch (k) {
    case ChannelKind::analog: return "analog";
    case ChannelKind::digital: return "digital";
  }
  return "unknown";
}

const char* to_string(InputRole r) noexcept {
  switch (r) {
    case InputRole::estop: return "estop";
    case InputRole::control: return "control";
    case InputRole::start: return "start";
  }
  return "unknown";
}

const ScalarValue* LinkSettings::find(std::string_view key) const {
  for (const LinkSetting& e : entries)
    if (e.key == key) return &e.value;
  return nullptr;
}

void LinkSettings::expect_only_keys(std::span<const std::string_view> allowed) const {
  for (const LinkSetting& e : entries) {
    bool known = false;
    for (std::string_view a : allowed) known = known || e.key == a;
    if (known) continue;
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw InputError(e.key_where, "unknown field '" + e.key + "' in " + what + "; expected one of: " + list);
  }
}

std::vector<std::size_t> bindings_moving(const RigKinematics& kinematics, std::size_t effector) {
  const kinematics::Model& model = kinematics.model;
  std::vector<char> on_path(model.dof(), 0);
  for (std::size_t j = model.effector(effector).joint; j != kinematics::Joint::kNoParent; j = model.joint(j).parent)
    if (model.joint(j).movable()) on_path[model.joint(j).q_index] = 1;
  std::vector<std::size_t> out;
  for (std::size_t b = 0; b < kinematics.bindings.size(); ++b)
    if (on_path[kinematics.bindings[b].q_index]) out.push_back(b);
  return out;
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

}  // namespace avar::rig
