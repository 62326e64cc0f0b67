#include "avar/firmware_iface/avar_device_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "avar/firmware_iface/wire_time.hpp"

namespace avar::firmware_iface {
namespace wire = avar_device;

AvarDeviceLink::AvarDeviceLink(ByteTransport& transport, AvarDeviceLinkConfig config)
    : transport_(transport), config_(std::move(config)), table_(config_.actuators) {
  const std::size_t n = config_.actuators.size();
  if (n == 0) throw std::invalid_argument("an avar-device link needs at least one actuator");
  if (n > wire::kMaxChannels)
    throw std::invalid_argument("an avar-device link carries at most " + std::to_string(wire::kMaxChannels) + " channels, not " +
                                std::to_string(n));
  std::vector<bool> used(n, false);
  for (const AvarDeviceActuator& a : config_.actuators) {
    if (a.device_channel < 0 || static_cast<std::size_t>(a.device_channel) >= n)
      throw std::invalid_argument("avar-device output " + std::to_string(a.device_channel) + " is outside 0.." +
                                  std::to_string(n - 1) + " (a device's outputs are numbered from 0, one per channel)");
    if (used[static_cast<std::size_t>(a.device_channel)])
      throw std::invalid_argument("avar-device output " + std::to_string(a.device_channel) + " is used twice");
    used[static_cast<std::size_t>(a.device_channel)] = true;
  }
  if (config_.tick.count() < 1 || config_.knot_every < 1)
    throw std::invalid_argument("an avar-device link needs a tick period and a knot spacing of at least 1");
  const auto spacing = config_.tick * config_.knot_every;
  if (config_.lead < 2 * spacing + config_.tick)
    throw std::invalid_argument("an avar-device link's lead (" + std::to_string(config_.lead.count() / 1000) +
                                " ms) must cover two knots and a tick (" +
                                std::to_string((2 * spacing + config_.tick).count() / 1000) + " ms)");
  ring_frames_ = static_cast<std::size_t>(config_.knot_every) + 3;
  ring_.assign(ring_frames_ * n, 0);
  knots_.resize(n);
  knot_values_.assign(n, 0);
  knot_slopes_.assign(n, 0);
  packet_.resize(3 * wire::kMaxFrame);
  wire::parser_reset(parser_, parser_buffer_.data(), static_cast<std::uint8_t>(parser_buffer_.size()));
  description_ = "avar-device (" + std::to_string(config_.baud) + " baud) on " + transport_.name();
}

Status AvarDeviceLink::await(std::uint8_t type) {
  const auto deadline = transport_.now() + config_.reply_timeout;
  std::array<std::uint8_t, 64> buffer{};
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - transport_.now());
    if (left.count() <= 0) return Status::timeout;
    std::size_t got = 0;
    if (const Status s = transport_.read_some(buffer, left, &got); s != Status::ok) return s;
    for (std::size_t i = 0; i < got; ++i)
      if (wire::parser_push(parser_, buffer[i]) && parser_.type == type) return Status::ok;
  }
}

Status AvarDeviceLink::start() {
  problem_.clear();
  transport_.discard_input();
  wire::parser_reset(parser_, parser_buffer_.data(), static_cast<std::uint8_t>(parser_buffer_.size()));
  std::array<std::uint8_t, wire::kMaxFrame> out{};
  if (const Status s = transport_.write(std::span(out.data(), wire::encode_hello(out.data()))); s != Status::ok) return s;
  if (const Status s = await(wire::kStatus); s != Status::ok) {
    if (s == Status::timeout) problem_ = "the device did not answer hello (is it running avar's streaming player?)";
    return s;
  }
  if (!wire::read_status(parser_.payload, parser_.length, status_)) {
    problem_ = "the device's status is not this protocol's";
    return Status::bad_data;
  }
  const std::size_t n = config_.actuators.size();
  const auto spacing = config_.tick * config_.knot_every;
  const std::size_t needed = static_cast<std::size_t>(config_.lead / spacing) + 2;
  if (status_.version != wire::kVersion)
    problem_ = "the device speaks avar-device version " + std::to_string(status_.version) + ", avar speaks " +
               std::to_string(wire::kVersion);
  else if (status_.channel_count != n)
    problem_ =
        "the device drives " + std::to_string(status_.channel_count) + " channels, the rig gives this link " + std::to_string(n);
  else if (status_.state == wire::kFault)
    problem_ =
        "the device switched its outputs off for a fault of its own (a servo board that does not answer on I2C: "
        "check its wiring and power), and stays so until it is reset";
  else if (status_.knot_capacity < needed)
    problem_ = "the device holds " + std::to_string(status_.knot_capacity) + " knots ahead; a lead of " +
               std::to_string(config_.lead.count() / 1000) + " ms with a knot every " + std::to_string(spacing.count() / 1000) +
               " ms needs " + std::to_string(needed) + " (shorten the lead or space the knots wider)";
  if (!problem_.empty()) return Status::bad_data;
  description_ = "avar-device (" + std::to_string(config_.baud) + " baud, device at " + std::to_string(status_.rate_hz) +
                 " Hz) on " + transport_.name();
  ticks_ = 0;
  knotted_ = false;
  // Knots no closer than the device's room allows: lead / spacing + 2 knots held at most.
  const auto lead_ticks = static_cast<std::size_t>(config_.lead / config_.tick);
  const std::size_t room = status_.knot_capacity > 2 ? status_.knot_capacity - 2u : 1u;
  min_spacing_ = std::max<std::size_t>(1, (lead_ticks + room - 1) / room);
  return Status::ok;
}

Status AvarDeviceLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, wire::kMaxFrame> out{};
  transport_.discard_input();
  wire::parser_reset(parser_, parser_buffer_.data(), static_cast<std::uint8_t>(parser_buffer_.size()));
  if (const Status s = transport_.write(std::span(out.data(), wire::encode_query(out.data()))); s != Status::ok) return s;
  if (const Status s = await(wire::kPositions); s != Status::ok) return s;
  std::array<std::uint16_t, wire::kMaxChannels> outputs{};
  std::uint8_t count = 0;
  if (!wire::read_positions(parser_.payload, parser_.length, outputs.data(), wire::kMaxChannels, count) ||
      count != config_.actuators.size())
    return Status::bad_data;
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    const AvarDeviceActuator& a = config_.actuators[i];
    frame[a.channel] = table_.to_channel(i, outputs[static_cast<std::size_t>(a.device_channel)]);
    known[a.channel] = true;
  }
  return Status::ok;
}

double AvarDeviceLink::value(std::uint64_t tick, std::size_t d) const noexcept {
  return ring_[static_cast<std::size_t>(tick % ring_frames_) * knots_.size() + d];
}

double AvarDeviceLink::slope(std::uint64_t tick, std::size_t d) const noexcept {
  // Central difference; the first tick has none before it.
  const double h = static_cast<double>(config_.tick.count()) / 1e6;
  if (tick == 0) return (value(1, d) - value(0, d)) / h;
  return (value(tick + 1, d) - value(tick - 1, d)) / (2 * h);
}

bool AvarDeviceLink::fits(std::uint64_t j) const noexcept {
  // The cubic the device plays between the last knot and a knot at j, against every tick between.
  const double span = static_cast<double>(j - last_knot_), h = static_cast<double>(config_.tick.count()) / 1e6;
  const double third = span * h / 3;
  for (std::size_t d = 0; d < knots_.size(); ++d) {
    const double p0 = knot_values_[d], p3 = std::clamp(std::round(value(j, d)), 0.0, 65535.0);
    const double p1 = p0 + knot_slopes_[d] * third;
    const double p2 = p3 - wire::kSlopeUnit * wire::slope_field(static_cast<std::int32_t>(std::lround(slope(j, d)))) * third;
    for (std::uint64_t i = last_knot_ + 1; i < j; ++i) {
      const double u = static_cast<double>(i - last_knot_) / span, v = 1 - u;
      const double cubic = v * v * v * p0 + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * p3;
      if (std::abs(cubic - value(i, d)) > config_.fit_tolerance) return false;
    }
  }
  return true;
}

std::size_t AvarDeviceLink::encode_knot(std::uint64_t j, std::uint8_t* out) noexcept {
  const std::size_t n = knots_.size();
  for (std::size_t d = 0; d < n; ++d) {
    knots_[d].value = static_cast<std::uint16_t>(std::clamp(std::lround(value(j, d)), 0L, 65535L));
    knots_[d].slope = wire::slope_field(static_cast<std::int32_t>(std::lround(slope(j, d))));
    knot_values_[d] = knots_[d].value;
    knot_slopes_[d] = static_cast<double>(wire::kSlopeUnit) * knots_[d].slope;
  }
  last_knot_ = j;
  knotted_ = true;
  const auto tick_us = static_cast<std::uint32_t>(config_.tick.count());
  const std::uint32_t time = static_cast<std::uint32_t>(j) * tick_us + static_cast<std::uint32_t>(config_.lead.count());
  return wire::encode_knots(time, knots_.data(), static_cast<std::uint8_t>(n), out);
}

Status AvarDeviceLink::send(std::span<const double> frame) noexcept {
  const std::size_t n = config_.actuators.size();
  std::size_t size = 0;
  std::array<std::uint8_t, (wire::kMaxChannels + 7) / 8> mask{};
  bool newly_released = false;
  double* now_values = &ring_[static_cast<std::size_t>(ticks_ % ring_frames_) * n];
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t d = static_cast<std::size_t>(config_.actuators[i].device_channel);
    if (table_.release_pending(i)) {
      mask[d / 8] = static_cast<std::uint8_t>(mask[d / 8] | (1u << (d % 8)));
      table_.set_release_told(i);
      newly_released = true;
    }
    // A released channel holds its last value (the device no longer drives it anyway).
    now_values[d] = table_.released(i) && ticks_ > 0 ? value(ticks_ - 1, d) : table_.to_device(i, frame);
  }
  if (newly_released) size += wire::encode_release_channels(mask.data(), static_cast<std::uint8_t>((n + 7) / 8), packet_.data());

  // Tick j = ticks_ - 1 (its slope needs this tick) may take a knot: the first tick always; then
  // the tick before j when the device's cubic from the last knot to j would leave the commanded
  // motion by more than the tolerance (no closer than the device's room allows), and j itself
  // once knot_every ticks have passed.
  if (ticks_ >= 1) {
    const std::uint64_t j = ticks_ - 1;
    std::size_t knot_size = 0;
    if (!knotted_ || j - last_knot_ >= static_cast<std::uint64_t>(config_.knot_every)) {
      knot_size = encode_knot(j, packet_.data() + size);
    } else if (j - 1 - last_knot_ >= min_spacing_ && !fits(j)) {
      knot_size = encode_knot(j - 1, packet_.data() + size);
    }
    if (knot_size > 0) {
      size += knot_size;
      // The clock last: the device takes it when its last byte arrives, the whole write's time
      // on the wire after this tick's.
      const double on_wire_s = wire_seconds(size + wire::kOverhead + 4, config_.baud);
      const std::uint32_t now = static_cast<std::uint32_t>(ticks_) * static_cast<std::uint32_t>(config_.tick.count());
      size += wire::encode_time(now + static_cast<std::uint32_t>(std::lround(on_wire_s * 1e6)), packet_.data() + size);
    }
  }
  ++ticks_;
  last_send_size_ = size;
  if (size == 0) {
    // Nothing to write this tick; a lost port still answers for itself (and is reopened).
    bool reopened = false;
    return reconnector_.ask(transport_, &reopened);
  }
  return reconnector_.write(transport_, std::span(packet_.data(), size));
}

Status AvarDeviceLink::release() noexcept {
  std::array<std::uint8_t, wire::kMaxFrame> out{};
  table_.release_all_told();
  return transport_.write(std::span(out.data(), wire::encode_release(out.data())));
}

void AvarDeviceLink::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

}  // namespace avar::firmware_iface
