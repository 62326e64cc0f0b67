#include "avar/firmware_iface/dmx_link.hpp"

#include <array>

namespace avar::firmware_iface {

DmxLink::DmxLink(ByteTransport& transport, DmxLinkConfig config)
    : transport_(transport), config_(std::move(config)), universe_(config_.actuators, config_.slot_count, dmx::kMinSlots) {
  packet_.resize(dmx::send_dmx_size(universe_.slots().size()));
  description_ = "DMX USB Pro (" + std::to_string(universe_.slots().size()) + " slots) on " + transport_.name();
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
  universe_.fill(frame);
  return write_frame();
}

Status DmxLink::write_frame() noexcept {
  last_send_size_ = dmx::encode_send_dmx(packet_, universe_.slots());
  return reconnector_.write(transport_, std::span(packet_.data(), last_send_size_));
}

Status DmxLink::release() noexcept {
  universe_.zero_all();
  return write_frame();
}

void DmxLink::release_channel(std::size_t channel) noexcept { universe_.release_channel(channel); }

}  // namespace avar::firmware_iface
