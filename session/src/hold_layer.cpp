#include "avar/session/hold_layer.hpp"

#include <algorithm>

namespace avar::session {

HoldLayer::HoldLayer(const rig::Rig& rig, control::LiveLayer* below)
    : below_(below), value_(rig.channels.size(), 0.0), held_(rig.channels.size(), 0) {
  min_.reserve(rig.channels.size());
  max_.reserve(rig.channels.size());
  for (const rig::ChannelSpec& c : rig.channels) {
    min_.push_back(c.min);
    max_.push_back(c.max);
  }
}

double HoldLayer::hold(std::size_t channel, double value) noexcept {
  value_[channel] = std::clamp(value, min_[channel], max_[channel]);
  held_[channel] = 1;
  return value_[channel];
}

void HoldLayer::release(std::size_t channel) noexcept { held_[channel] = 0; }

void HoldLayer::apply(double now_s, std::span<double> frame) noexcept {
  if (below_) below_->apply(now_s, frame);
  for (std::size_t c = 0; c < held_.size(); ++c)
    if (held_[c]) frame[c] = value_[c];
}

}  // namespace avar::session
