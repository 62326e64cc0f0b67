#include "avar/firmware_iface/maestro_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace avar::firmware_iface {

MaestroLink::MaestroLink(ByteTransport& transport, MaestroLinkConfig config)
    : transport_(transport), config_(std::move(config)), table_(config_.actuators) {
  const std::size_t n = config_.actuators.size();
  check_maestro_channels(config_.actuators, config_.channel_count);
  slots_.resize(n);
  for (std::size_t i = 0; i < n; ++i) slots_[i] = i;
  std::sort(slots_.begin(), slots_.end(), [&](std::size_t a, std::size_t b) {
    return config_.actuators[a].device_channel < config_.actuators[b].device_channel;
  });
  // Runs of consecutive device channels share one Set Multiple Targets packet; the Micro
  // Maestro (6 channels) has no such command, so there every channel is its own run.
  const bool multiple = config_.channel_count > 6;
  for (std::size_t s = 0; s < n; ++s) {
    const int ch = config_.actuators[slots_[s]].device_channel;
    if (multiple && !runs_.empty() && runs_.back().first_channel + runs_.back().count == static_cast<std::size_t>(ch))
      ++runs_.back().count;
    else runs_.push_back({static_cast<std::uint8_t>(ch), s, 1});
  }
  targets_.resize(n);
  packet_.resize(runs_.size() * maestro::kMaxPacketSize);
  description_ = "Maestro (" + std::to_string(config_.channel_count) + " channels) on " + transport_.name();
}

Status MaestroLink::query(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply) {
  transport_.discard_input();
  if (const Status s = transport_.write(request); s != Status::ok) return s;
  return transport_.read_exact(reply, config_.reply_timeout);
}

Status MaestroLink::read_errors(std::uint16_t& errors) {
  std::array<std::uint8_t, maestro::kMaxPacketSize> request{};
  const std::size_t len = maestro::encode_get_errors(request, config_.framing);
  std::array<std::uint8_t, 2> reply{};
  if (const Status s = query(std::span(request.data(), len), reply); s != Status::ok) return s;
  errors = maestro::decode_errors_reply(reply);
  return Status::ok;
}

Status MaestroLink::send_baud_detect() noexcept {
  if (!config_.baud_detect) return Status::ok;
  const std::array<std::uint8_t, 1> detect{0xAA};
  return transport_.write(detect);
}

Status MaestroLink::send_limits() noexcept {
  std::array<std::uint8_t, maestro::kMaxPacketSize> packet{};
  for (const MaestroActuator& a : config_.actuators) {
    const auto ch = static_cast<std::uint8_t>(a.device_channel);
    std::size_t len = maestro::encode_set_speed(packet, config_.framing, ch, maestro_speed_units(a));
    if (const Status s = transport_.write(std::span(packet.data(), len)); s != Status::ok) return s;
    len = maestro::encode_set_acceleration(packet, config_.framing, ch, maestro_acceleration_units(a));
    if (const Status s = transport_.write(std::span(packet.data(), len)); s != Status::ok) return s;
  }
  return Status::ok;
}

Status MaestroLink::start() {
  if (const Status s = send_baud_detect(); s != Status::ok) return s;
  std::uint16_t errors = 0;
  if (const Status s = read_errors(errors); s != Status::ok) return s;
  return send_limits();
}

Status MaestroLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, maestro::kMaxPacketSize> request{};
  for (const MaestroActuator& a : config_.actuators) {
    const std::size_t len = maestro::encode_get_position(request, config_.framing, static_cast<std::uint8_t>(a.device_channel));
    std::array<std::uint8_t, 2> reply{};
    if (const Status s = query(std::span(request.data(), len), reply); s != Status::ok) return s;
    const std::uint16_t quarter_us = maestro::decode_position_reply(reply);
    if (quarter_us == 0) continue;  // no pulses yet: the device does not know where the servo is
    frame[a.channel] = a.calibration.to_channel(quarter_us / 4.0);
    known[a.channel] = true;
  }
  return Status::ok;
}

Status MaestroLink::send(std::span<const double> frame) noexcept {
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    targets_[s] = maestro_target(table_, slots_[s], frame);
  }
  return write_targets();
}

Status MaestroLink::write_targets() noexcept {
  std::size_t size = 0;
  const std::span<std::uint8_t> out(packet_);
  for (const Run& run : runs_) {
    const std::span<std::uint8_t> room = out.subspan(size);
    const std::size_t len = run.count == 1
                                ? maestro::encode_set_target(room, config_.framing, run.first_channel, targets_[run.first_slot])
                                : maestro::encode_set_multiple_targets(room, config_.framing, run.first_channel,
                                                                       std::span(targets_).subspan(run.first_slot, run.count));
    if (len == 0) return Status::out_of_range;
    size += len;
  }
  last_send_size_ = size;
  bool reopened = false;
  if (reconnector_.ask(transport_, &reopened) != Status::ok) return Status::io_error;
  Status s = Status::ok;
  if (reopened) {
    s = send_baud_detect();
    if (s == Status::ok) s = send_limits();
  }
  if (s == Status::ok) s = transport_.write(out.first(size));
  if (s == Status::io_error) reconnector_.lost();
  if (s == Status::ok) reconnector_.sent(size);
  return s;
}

void MaestroLink::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

Status MaestroLink::release() noexcept {
  // Target 0 stops the pulses: a hobby servo without pulses holds no position.
  std::fill(targets_.begin(), targets_.end(), std::uint16_t{0});
  return write_targets();
}

}  // namespace avar::firmware_iface
