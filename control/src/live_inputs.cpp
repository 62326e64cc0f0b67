#include "avar/control/live_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace avar::control {
namespace {

std::vector<std::string> control_names(const std::vector<LiveChannel>& channels, const std::vector<ControlMapping>& mappings) {
  std::vector<std::string> names;
  for (const ControlMapping& m : mappings) {
    names.push_back(m.control);
    if (!m.hold.empty()) names.push_back(m.hold);
  }
  for (const LiveChannel& c : channels) names.push_back("channel/" + c.name);
  return names;
}

constexpr const char* kAxisNames[3] = {"x", "y", "z"};

std::vector<MixerLayer> layers_of(const std::vector<LiveChannel>& channels, const std::vector<ControlMapping>& mappings) {
  std::vector<MixerLayer> layers;
  for (const ControlMapping& m : mappings) {
    if (m.output == MappingOutput::target) continue;
    if (m.channel >= channels.size())
      throw std::invalid_argument("the mapping of control '" + m.control + "' names no channel of the rig");
    layers.push_back({m.control + " -> " + channels[m.channel].name, m.channel, m.priority, m.blend, m.crossfade_s, m.timeout_s});
  }
  for (std::size_t c = 0; c < channels.size(); ++c)
    layers.push_back({"channel/" + channels[c].name, c, kDirectPriority, Blend::override, kDirectCrossfadeS, kDirectTimeoutS});
  return layers;
}

std::vector<MixerLayer> target_layers_of(const std::vector<std::string>& effectors, const std::vector<ControlMapping>& mappings) {
  std::vector<MixerLayer> layers;
  for (const ControlMapping& m : mappings) {
    if (m.output != MappingOutput::target) continue;
    if (m.effector >= effectors.size() || m.axis >= 3)
      throw std::invalid_argument("the mapping of control '" + m.control + "' names no effector axis of the rig's kinematics");
    if (!std::isfinite(m.low) || !std::isfinite(m.high))
      throw std::invalid_argument("the mapping of control '" + m.control + "' needs a finite range (metres)");
    layers.push_back({m.control + " -> " + effectors[m.effector] + "." + kAxisNames[m.axis], 3 * m.effector + m.axis, m.priority,
                      m.blend, m.crossfade_s, m.timeout_s});
  }
  return layers;
}

}  // namespace

LiveInputs::LiveInputs(std::vector<LiveChannel> channels, std::vector<ControlMapping> mappings,
                       std::vector<std::string> effectors)
    : channels_(std::move(channels)),
      mappings_(std::move(mappings)),
      effectors_(std::move(effectors)),
      mailbox_(control_names(channels_, mappings_)),
      mixer_(channels_.size(), layers_of(channels_, mappings_)),
      target_mixer_(3 * effectors_.size(), target_layers_of(effectors_, mappings_)),
      state_(mappings_.size()),
      direct_slot_(channels_.size()),
      direct_seen_(channels_.size(), 0),
      values_(mailbox_.size(), std::numeric_limits<double>::quiet_NaN()),
      last_out_(channels_.size(), 0),
      touched_(channels_.size(), 0),
      targets_touched_(effectors_.size(), 0),
      last_points_(3 * effectors_.size(), std::numeric_limits<double>::quiet_NaN()) {
  std::size_t channel_layers = 0, target_layers = 0;
  for (std::size_t i = 0; i < mappings_.size(); ++i) {
    state_[i].layer = mappings_[i].output == MappingOutput::target ? target_layers++ : channel_layers++;
    state_[i].slot = mailbox_.find(mappings_[i].control);
    state_[i].hold_slot = mappings_[i].hold.empty() ? mailbox_.size() : mailbox_.find(mappings_[i].hold);
  }
  for (std::size_t c = 0; c < channels_.size(); ++c) direct_slot_[c] = mailbox_.find("channel/" + channels_[c].name);
}

void LiveInputs::drive(std::size_t i, double now_s, double dt, ControlMixer& mixer, std::span<const double> last) noexcept {
  const ControlMapping& m = mappings_[i];
  MappingState& s = state_[i];
  const std::size_t layer = s.layer;
  if (s.hold_slot < mailbox_.size()) {
    const ControlReading h = mailbox_.read(s.hold_slot);
    if (h.sequence == 0 || !(h.value >= 0.5)) {
      mixer.release(layer);
      s.started = false;
      return;
    }
  }
  const ControlReading r = mailbox_.read(s.slot);
  if (r.sequence == 0) return;
  const bool fresh = r.sequence != s.seen;
  if (fresh) taking_ns_ = std::max(taking_ns_, r.arrived_ns);
  s.seen = r.sequence;
  const ShapedValue shaped = shape_control(r.value, r.bipolar, m.shape);
  if (!s.started || m.shape.smoothing_s <= 0) {
    s.smoothed = shaped.value;
  } else {
    s.smoothed += (shaped.value - s.smoothed) * dt / (m.shape.smoothing_s + dt);
  }
  double out = 0;
  bool activity = fresh;
  if (m.mode == MappingMode::absolute) {
    out = shaped.bipolar ? 0.5 * (m.low + m.high) + s.smoothed * 0.5 * (m.high - m.low) : m.low + s.smoothed * (m.high - m.low);
  } else {
    // Taken from where the output is, then driven at the deflection's speed, within its bounds.
    const bool target = m.output == MappingOutput::target;
    const double lo = target ? std::min(m.low, m.high) : channels_[m.channel].min;
    const double hi = target ? std::max(m.low, m.high) : channels_[m.channel].max;
    const std::size_t index = mixer.layer(layer).channel;
    if (!s.started || !mixer.active(layer)) s.position = std::isfinite(last[index]) ? last[index] : 0.5 * (lo + hi);
    s.position = std::clamp(s.position + s.smoothed * m.rate * dt, lo, hi);
    out = s.position;
    activity = activity || s.smoothed != 0;
  }
  s.started = true;
  if (activity) mixer.set(layer, out, now_s);
  else mixer.update(layer, out);
}

void LiveInputs::apply_targets(double now_s, std::span<double> points) noexcept {
  if (target_mixer_.size() == 0 || points.size() != last_points_.size()) return;
  const double dt = targets_applied_ ? std::max(0.0, now_s - last_targets_now_) : 0.0;
  if (!targets_applied_) std::copy(points.begin(), points.end(), last_points_.begin());
  last_targets_now_ = now_s;
  targets_applied_ = true;
  for (std::size_t i = 0; i < mappings_.size(); ++i)
    if (mappings_[i].output == MappingOutput::target) drive(i, now_s, dt, target_mixer_, last_points_);
  target_mixer_.mix(points, now_s);
  for (std::size_t i = 0; i < target_mixer_.size(); ++i)
    if (target_mixer_.weight(i) > 0) targets_touched_[target_mixer_.layer(i).channel / 3] = 1;
  std::copy(points.begin(), points.end(), last_points_.begin());
}

void LiveInputs::apply(double now_s, std::span<double> frame) noexcept {
  const double dt = applied_ ? std::max(0.0, now_s - last_now_) : 0.0;
  if (!applied_)
    std::copy(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(std::min(frame.size(), last_out_.size())),
              last_out_.begin());
  last_now_ = now_s;
  applied_ = true;
  for (std::size_t k = 0; k < mailbox_.size(); ++k) {
    const ControlReading r = mailbox_.read(k);
    if (r.sequence > 0) values_[k] = r.value;
  }

  for (std::size_t i = 0; i < mappings_.size(); ++i)
    if (mappings_[i].output == MappingOutput::channel) drive(i, now_s, dt, mixer_, last_out_);

  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const ControlReading r = mailbox_.read(direct_slot_[c]);
    if (r.sequence == direct_seen_[c]) continue;
    direct_seen_[c] = r.sequence;
    taking_ns_ = std::max(taking_ns_, r.arrived_ns);
    if (!std::isfinite(r.value)) continue;
    mixer_.set(mixer_.size() - channels_.size() + c, std::clamp(r.value, channels_[c].min, channels_[c].max), now_s);
  }

  mixer_.mix(frame, now_s);
  for (std::size_t i = 0; i < mixer_.size(); ++i)
    if (mixer_.weight(i) > 0) touched_[mixer_.layer(i).channel] = 1;
  std::copy(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(std::min(frame.size(), last_out_.size())),
            last_out_.begin());
  newest_taken_ns_ = taking_ns_;
  taking_ns_ = 0;
}

}  // namespace avar::control
