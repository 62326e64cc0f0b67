#include "avar/sim/sim_avar_device.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "avar/sim/reply_queue.hpp"

namespace avar::sim {
namespace wire = firmware_iface::avar_device;

SimAvarDevice::SimAvarDevice(SimAvarDeviceConfig config) : config_(std::move(config)) {
  const std::size_t n = config_.channels.size();
  if (n == 0 || n > wire::kMaxChannels)
    throw std::invalid_argument("a simulated avar-device drives 1 to " + std::to_string(wire::kMaxChannels) + " channels, not " +
                                std::to_string(n));
  stored_.resize(n);
  channels_.resize(n);
  times_.resize(config_.knot_capacity);
  knots_.resize(static_cast<std::size_t>(config_.knot_capacity) * n);
  frame_.resize(device::stream_frame_room(static_cast<std::uint8_t>(n)));
  for (std::size_t c = 0; c < n; ++c) {
    device::write_limits(config_.channels[c].limits, stored_[c].data());
    channels_[c].limits = stored_[c].data();
  }
  const device::StreamStatus status =
      device::stream_init(player_, channels_.data(), static_cast<std::uint8_t>(n), times_.data(), knots_.data(),
                          config_.knot_capacity, frame_.data(), config_.rate_hz, config_.watchdog_ms * 1000u);
  if (status == device::kStreamBadLimits) throw std::invalid_argument("a simulated avar-device's channel limits are not usable");
  if (status != device::kStreamOk)
    throw std::invalid_argument("a simulated avar-device needs a control rate above 0 and room for at least 2 knots");
  for (std::size_t c = 0; c < n; ++c) servos_.emplace_back(config_.servo, pulse_us(c));
}

std::uint32_t SimAvarDevice::now_us() const {
  return config_.clock_start_us + static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::llround(now_s_ * 1e6)));
}

double SimAvarDevice::pulse_us(std::size_t c) const {
  if (channels_[c].released) return 0;
  const SimAvarDeviceChannel& ch = config_.channels[c];
  return ch.pulse_at_low_us + (ch.pulse_at_high_us - ch.pulse_at_low_us) * channels_[c].output / 65535.0;
}

void SimAvarDevice::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  std::uint8_t reply[wire::kMaxFrame];
  const std::uint32_t now = now_us();
  for (std::uint8_t b : bytes) {
    const std::uint16_t n = device::stream_receive(player_, b, now, reply);
    replies_.insert(replies_.end(), reply, reply + n);
  }
}

std::size_t SimAvarDevice::take_replies(std::span<std::uint8_t> out) { return take_from(replies_, out); }

void SimAvarDevice::advance(double dt_s) {
  if (!(dt_s > 0)) return;
  const double end = now_s_ + dt_s;
  const double period = 1.0 / config_.rate_hz;
  // Control ticks as they fall due; the servos follow each tick's pulses in between.
  while (next_tick_s_ <= end) {
    for (std::size_t c = 0; c < servos_.size(); ++c) servos_[c].step(next_tick_s_ - now_s_, pulse_us(c));
    now_s_ = next_tick_s_;
    device::stream_tick(player_, now_us());
    ++ticks_;
    next_tick_s_ = static_cast<double>(ticks_) * period;
  }
  for (std::size_t c = 0; c < servos_.size(); ++c) servos_[c].step(end - now_s_, pulse_us(c));
  now_s_ = end;
}

}  // namespace avar::sim
