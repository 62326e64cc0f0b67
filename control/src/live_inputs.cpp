#include "avar/control/live_inputs.hpp"

#include <algorithm>
#include <cmath>
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

std::vector<MixerLayer> layers_of(const std::vector<LiveChannel>& channels, const std::vector<ControlMapping>& mappings) {
  std::vector<MixerLayer> layers;
  for (const ControlMapping& m : mappings) {
    if (m.channel >= channels.size())
      throw std::invalid_argument("the mapping of control '" + m.control + "' names no channel of the rig");
    layers.push_back({m.control + " -> " + channels[m.channel].name, m.channel, m.priority, m.blend, m.crossfade_s, m.timeout_s});
  }
  for (std::size_t c = 0; c < channels.size(); ++c)
    layers.push_back({"channel/" + channels[c].name, c, kDirectPriority, Blend::override, kDirectCrossfadeS, kDirectTimeoutS});
  return layers;
}

}  // namespace

LiveInputs::LiveInputs(std::vector<LiveChannel> channels, std::vector<ControlMapping> mappings)
    : channels_(std::move(channels)),
      mappings_(std::move(mappings)),
      mailbox_(control_names(channels_, mappings_)),
      mixer_(channels_.size(), layers_of(channels_, mappings_)),
      state_(mappings_.size()),
      direct_slot_(channels_.size()),
      direct_seen_(channels_.size(), 0),
      values_(mailbox_.size(), std::numeric_limits<double>::quiet_NaN()),
      last_out_(channels_.size(), 0),
      touched_(channels_.size(), 0) {
  for (std::size_t i = 0; i < mappings_.size(); ++i) {
    state_[i].slot = mailbox_.find(mappings_[i].control);
    state_[i].hold_slot = mappings_[i].hold.empty() ? mailbox_.size() : mailbox_.find(mappings_[i].hold);
  }
  for (std::size_t c = 0; c < channels_.size(); ++c) direct_slot_[c] = mailbox_.find("channel/" + channels_[c].name);
}

void LiveInputs::apply(double now_s, std::span<double> frame) noexcept {
  const double dt = applied_ ? std::max(0.0, now_s - last_now_) : 0.0;
  if (!applied_)
    std::copy(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(std::min(frame.size(), last_out_.size())),
              last_out_.begin());
  last_now_ = now_s;
  applied_ = true;
  newest_taken_ns_ = 0;
  for (std::size_t k = 0; k < mailbox_.size(); ++k) {
    const ControlReading r = mailbox_.read(k);
    if (r.sequence > 0) values_[k] = r.value;
  }

  for (std::size_t i = 0; i < mappings_.size(); ++i) {
    const ControlMapping& m = mappings_[i];
    MappingState& s = state_[i];
    if (s.hold_slot < mailbox_.size()) {
      const ControlReading h = mailbox_.read(s.hold_slot);
      if (h.sequence == 0 || !(h.value >= 0.5)) {
        mixer_.release(i);
        s.started = false;
        continue;
      }
    }
    const ControlReading r = mailbox_.read(s.slot);
    if (r.sequence == 0) continue;
    const bool fresh = r.sequence != s.seen;
    if (fresh) newest_taken_ns_ = std::max(newest_taken_ns_, r.arrived_ns);
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
      // Taken from where the channel is, then driven at the deflection's speed.
      if (!s.started || !mixer_.active(i)) s.position = last_out_[m.channel];
      s.position = std::clamp(s.position + s.smoothed * m.rate * dt, channels_[m.channel].min, channels_[m.channel].max);
      out = s.position;
      activity = activity || s.smoothed != 0;
    }
    s.started = true;
    if (activity) mixer_.set(i, out, now_s);
    else mixer_.update(i, out);
  }

  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const ControlReading r = mailbox_.read(direct_slot_[c]);
    if (r.sequence == direct_seen_[c]) continue;
    direct_seen_[c] = r.sequence;
    newest_taken_ns_ = std::max(newest_taken_ns_, r.arrived_ns);
    if (!std::isfinite(r.value)) continue;
    mixer_.set(mappings_.size() + c, std::clamp(r.value, channels_[c].min, channels_[c].max), now_s);
  }

  mixer_.mix(frame, now_s);
  for (std::size_t i = 0; i < mixer_.size(); ++i)
    if (mixer_.weight(i) > 0) touched_[mixer_.layer(i).channel] = 1;
  std::copy(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(std::min(frame.size(), last_out_.size())),
            last_out_.begin());
}

}  // namespace avar::control
