#include "avar/firmware_iface/ssc32_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace avar::firmware_iface {

Ssc32Link::Ssc32Link(ByteTransport& transport, Ssc32LinkConfig config)
    : transport_(transport), config_(std::move(config)), table_(config_.actuators) {
  const std::size_t n = config_.actuators.size();
  if (n == 0) throw std::invalid_argument("an SSC-32 link needs at least one actuator");
  std::array<bool, ssc32::kChannels> used{};
  for (const Ssc32Actuator& a : config_.actuators) {
    if (a.device_channel < 0 || a.device_channel >= ssc32::kChannels)
      throw std::invalid_argument("SSC-32 channel " + std::to_string(a.device_channel) + " is outside 0..31");
    if (used[static_cast<std::size_t>(a.device_channel)])
      throw std::invalid_argument("SSC-32 channel " + std::to_string(a.device_channel) + " is used twice");
    used[static_cast<std::size_t>(a.device_channel)] = true;
  }
  moves_.resize(n);
  channels_.resize(n);
  packet_.resize(2 * ssc32::kMaxLineSize);
  description_ = "SSC-32 (" + std::to_string(config_.baud) + " baud) on " + transport_.name();
}

Status Ssc32Link::query_moving(bool& moving) {
  std::array<std::uint8_t, 4> request{};
  const std::size_t len = ssc32::encode_query_movement(request);
  transport_.discard_input();
  if (const Status s = transport_.write(std::span(request.data(), len)); s != Status::ok) return s;
  std::array<std::uint8_t, 1> reply{};
  if (const Status s = transport_.read_exact(reply, config_.reply_timeout); s != Status::ok) return s;
  if (reply[0] != ssc32::kMoveDone && reply[0] != ssc32::kMoveInProgress) return Status::bad_data;
  moving = reply[0] == ssc32::kMoveInProgress;
  return Status::ok;
}

Status Ssc32Link::start() {
  bool moving = false;
  return query_moving(moving);
}

Status Ssc32Link::read_positions(std::span<double> frame, std::span<bool> known) {
  const std::size_t n = config_.actuators.size();
  for (std::size_t i = 0; i < n; ++i) channels_[i] = static_cast<std::uint8_t>(config_.actuators[i].device_channel);
  std::array<std::uint8_t, ssc32::kMaxLineSize> request{};
  const std::size_t len = ssc32::encode_query_pulse(request, channels_);
  transport_.discard_input();
  if (const Status s = transport_.write(std::span(request.data(), len)); s != Status::ok) return s;
  std::array<std::uint8_t, ssc32::kChannels> reply{};
  if (const Status s = transport_.read_exact(std::span(reply.data(), n), config_.reply_timeout); s != Status::ok) return s;
  for (std::size_t i = 0; i < n; ++i) {
    if (reply[i] == 0) continue;  // no pulse: the board does not know where the servo is
    const Ssc32Actuator& a = config_.actuators[i];
    frame[a.channel] = a.calibration.to_channel(ssc32::pulse_from_reply(reply[i]));
    known[a.channel] = true;
  }
  return Status::ok;
}

Status Ssc32Link::send(std::span<const double> frame) noexcept {
  const std::size_t n = config_.actuators.size();
  std::size_t size = 0, driven = 0, newly_low = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (table_.release_pending(i)) {
      channels_[newly_low++] = static_cast<std::uint8_t>(config_.actuators[i].device_channel);
      table_.set_release_told(i);
    }
  if (newly_low > 0) size += ssc32::encode_outputs_low(packet_, std::span(channels_.data(), newly_low));
  for (std::size_t i = 0; i < n; ++i) {
    if (table_.released(i)) continue;
    const Ssc32Actuator& a = config_.actuators[i];
    const double us = table_.to_device(i, frame);
    const double speed = a.speed_us_per_s ? std::clamp(*a.speed_us_per_s, 1.0, 65535.0) : 0;
    moves_[driven++] = {static_cast<std::uint8_t>(a.device_channel),
                        static_cast<std::uint16_t>(std::clamp(std::lround(us), 500L, 2500L)),
                        static_cast<std::uint16_t>(std::lround(speed))};
  }
  if (driven > 0)
    size += ssc32::encode_group_move(std::span(packet_).subspan(size), std::span(moves_.data(), driven),
                                     static_cast<std::uint32_t>(config_.move_time.count()));
  last_send_size_ = size;
  if (size == 0) return Status::ok;
  return reconnector_.write(transport_, std::span(packet_.data(), size));
}

Status Ssc32Link::release() noexcept {
  const std::size_t n = config_.actuators.size();
  for (std::size_t i = 0; i < n; ++i) channels_[i] = static_cast<std::uint8_t>(config_.actuators[i].device_channel);
  const std::size_t size = ssc32::encode_outputs_low(packet_, std::span(channels_.data(), n));
  return transport_.write(std::span(packet_.data(), size));
}

void Ssc32Link::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

}  // namespace avar::firmware_iface
