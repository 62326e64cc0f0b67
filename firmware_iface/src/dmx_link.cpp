#include "avar/firmware_iface/dmx_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace avar::firmware_iface {

DmxLink::DmxLink(ByteTransport& transport, DmxLinkConfig config)
    : transport_(transport), config_(std::move(config)), table_(config_.actuators) {
  if (config_.actuators.empty()) throw std::invalid_argument("a DMX link needs at least one actuator");
  std::array<bool, dmx::kUniverseSize + 1> used{};
  std::size_t highest = 0;
  for (const DmxActuator& a : config_.actuators) {
    const int last = a.address + (a.fine ? 1 : 0);
    if (a.address < 1 || last > static_cast<int>(dmx::kUniverseSize))
      throw std::invalid_argument("DMX address " + std::to_string(a.address) + (a.fine ? " (16-bit)" : "") +
                                  " does not fit in 1..512");
    for (int s = a.address; s <= last; ++s) {
      if (used[static_cast<std::size_t>(s)]) throw std::invalid_argument("DMX slot " + std::to_string(s) + " is used twice");
      used[static_cast<std::size_t>(s)] = true;
    }
    highest = std::max(highest, static_cast<std::size_t>(last));
  }
  if (config_.slot_count > dmx::kUniverseSize || (config_.slot_count != 0 && config_.slot_count < highest))
    throw std::invalid_argument("DMX slot count " + std::to_string(config_.slot_count) + " must cover slot " +
                                std::to_string(highest) + " and stay within 512");
  slots_.assign(std::max(config_.slot_count == 0 ? highest : config_.slot_count, dmx::kMinSlots), 0);
  packet_.resize(dmx::send_dmx_size(slots_.size()));
  description_ = "DMX USB Pro (" + std::to_string(slots_.size()) + " slots) on " + transport_.name();
}

Status DmxLink::start() {
  std::array<std::uint8_t, 8> request{};
  const std::size_t len = dmx::encode_get_widget_parameters(request);
  transport_.discard_input();
  if (const Status s = transport_.write(std::span(request.data(), len)); s != Status::ok) return s;
  // The reply: 7E 03 05 00, five data bytes, E7.
  std::array<std::uint8_t, dmx::kOverhead + 5> reply{};
  if (const Status s = transport_.read_exact(reply, config_.reply_timeout); s != Status::ok) return s;
  dmx::Message m;
  std::size_t used = 0;
  if (dmx::decode_message(reply, &m, &used) != dmx::DecodeResult::ok || m.label != dmx::kGetWidgetParameters ||
      !dmx::decode_widget_parameters(m.data, &parameters_))
    return Status::bad_data;
  return Status::ok;
}

Status DmxLink::read_positions(std::span<double>, std::span<bool>) { return Status::ok; }

Status DmxLink::send(std::span<const double> frame) noexcept {
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    const DmxActuator& a = config_.actuators[i];
    long level = 0;
    if (!table_.released(i)) level = std::clamp(std::lround(table_.to_device(i, frame)), 0L, a.fine ? 65535L : 255L);
    const auto at = static_cast<std::size_t>(a.address - 1);
    if (a.fine) {
      slots_[at] = static_cast<std::uint8_t>(level >> 8);
      slots_[at + 1] = static_cast<std::uint8_t>(level & 0xFF);
    } else {
      slots_[at] = static_cast<std::uint8_t>(level);
    }
  }
  return write_frame();
}

Status DmxLink::write_frame() noexcept {
  last_send_size_ = dmx::encode_send_dmx(packet_, slots_);
  return reconnector_.write(transport_, std::span(packet_.data(), last_send_size_));
}

Status DmxLink::release() noexcept {
  for (const DmxActuator& a : config_.actuators) {
    slots_[static_cast<std::size_t>(a.address - 1)] = 0;
    if (a.fine) slots_[static_cast<std::size_t>(a.address)] = 0;
  }
  return write_frame();
}

void DmxLink::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

}  // namespace avar::firmware_iface
