#include "avar/sim/sim_dmx.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/wire_time.hpp"
#include "avar/sim/reply_queue.hpp"

namespace avar::sim {
namespace dmx = firmware_iface::dmx;

SimDmx::SimDmx(SimDmxConfig config) : config_(std::move(config)) {
  for (const SimDmxFixture& f : config_.fixtures) {
    if (f.address < 1 || f.address + (f.fine ? 1 : 0) > static_cast<int>(dmx::kUniverseSize))
      throw std::invalid_argument("DMX fixture at address " + std::to_string(f.address) + " does not fit in 1..512");
    servos_.emplace_back(config_.servo, f.initial_position_us);
  }
  input_.reserve(2 * dmx::kMaxMessageSize);
}

int SimDmx::fixture_level(std::size_t fixture) const {
  const SimDmxFixture& f = config_.fixtures[fixture];
  return f.fine ? slot(f.address) << 8 | slot(f.address + 1) : slot(f.address);
}

double SimDmx::fixture_pulse_us(std::size_t fixture) const {
  const SimDmxFixture& f = config_.fixtures[fixture];
  const double full = f.fine ? 65535.0 : 255.0;
  return f.pulse_at_zero_us + (f.pulse_at_full_us - f.pulse_at_zero_us) * fixture_level(fixture) / full;
}

double SimDmx::wire_time(std::size_t bytes) const { return firmware_iface::wire_seconds(bytes, config_.baud); }

double SimDmx::dmx_period() const {
  const double packet = dmx::dmx_packet_seconds(std::max<std::size_t>(slot_count_, 1));
  const std::uint8_t rate = config_.parameters.output_rate;
  return rate == 0 ? packet : std::max(packet, 1.0 / rate);
}

void SimDmx::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  input_.insert(input_.end(), bytes.begin(), bytes.end());
  std::size_t at = 0;
  for (;;) {
    dmx::Message m;
    std::size_t used = 0;
    const dmx::DecodeResult r = dmx::decode_message(std::span(input_).subspan(at), &m, &used);
    at += used;
    if (r == dmx::DecodeResult::need_more) break;
    if (r == dmx::DecodeResult::bad_framing) {
      framing_errors_ += used;
      continue;
    }
    handle(m.label, m.data);
  }
  input_.erase(input_.begin(), input_.begin() + static_cast<long>(at));
}

void SimDmx::handle(std::uint8_t label, std::span<const std::uint8_t> data) {
  switch (label) {
    case dmx::kOutputOnlySendDmx: {
      if (data.size() < 1 + dmx::kMinSlots || data.size() > 1 + dmx::kUniverseSize) return;
      ++frames_;
      start_code_ = data[0];
      slot_count_ = data.size() - 1;
      std::copy(data.begin() + 1, data.end(), universe_.begin());
      return;
    }
    case dmx::kGetWidgetParameters: {
      if (data.size() != 2) return;
      const std::size_t user = get_u16_le(&data[0]);
      if (user > 508) return;
      std::array<std::uint8_t, 508> config_bytes{};  // no user configuration stored: zeros
      std::array<std::uint8_t, dmx::kMaxMessageSize> out{};
      const std::size_t n = dmx::encode_widget_parameters_reply(out, config_.parameters, std::span(config_bytes.data(), user));
      replies_.insert(replies_.end(), out.begin(), out.begin() + static_cast<long>(n));
      return;
    }
    case dmx::kSetWidgetParameters: {
      if (data.size() < 5) return;
      const std::uint8_t brk = data[2], mab = data[3], rate = data[4];
      if (brk < 9 || brk > 127 || mab < 1 || mab > 127 || rate > 40) return;
      config_.parameters.break_time = brk, config_.parameters.mab_time = mab, config_.parameters.output_rate = rate;
      return;
    }
    case dmx::kGetSerialNumber: {
      if (!data.empty()) return;
      std::array<std::uint8_t, 4> serial{};
      put_u32_le(serial.data(), config_.serial_number);
      std::array<std::uint8_t, 16> out{};
      const std::size_t n = dmx::encode_message(out, dmx::kGetSerialNumber, serial);
      replies_.insert(replies_.end(), out.begin(), out.begin() + static_cast<long>(n));
      return;
    }
    default:
      return;  // labels this model does not act on (RDM, receive modes, firmware)
  }
}

std::size_t SimDmx::take_replies(std::span<std::uint8_t> out) {
  return take_from(replies_, out);
}

void SimDmx::advance(double dt_s) {
  if (!(dt_s > 0)) return;
  if (frames_ > 0) {
    since_packet_ += dt_s;
    const double period = dmx_period();
    const auto packets = static_cast<std::uint64_t>(std::floor(since_packet_ / period));
    dmx_packets_ += packets;
    since_packet_ -= static_cast<double>(packets) * period;
  }
  const int steps = static_cast<int>(std::ceil(dt_s / 0.001));
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    // Before the first DMX packet a decoder outputs no pulses.
    const double pulse = frames_ > 0 ? fixture_pulse_us(i) : 0;
    for (int s = 0; s < steps; ++s) servos_[i].step(dt_s / steps, pulse);
  }
}

}  // namespace avar::sim
