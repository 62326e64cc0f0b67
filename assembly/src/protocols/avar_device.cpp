#include "avar/assembly/avar_device_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/device/show_export.hpp"
#include "avar/sim/sim_avar_device.hpp"

namespace avar::assembly {
namespace {

/// The link's actuators in the device's output order (0..n-1, each once), checked.
std::vector<const rig::ActuatorSpec*> by_output(const rig::Rig& rig, std::size_t link) {
  std::size_t count = 0;
  for (const rig::ActuatorSpec& a : rig.actuators) count += a.link.value == link ? 1 : 0;
  std::vector<const rig::ActuatorSpec*> out(count, nullptr);
  for (const rig::ActuatorSpec& a : rig.actuators)
    if (a.link.value == link) {
      const auto n = static_cast<int>(out.size());
      if (a.device_channel < 0 || a.device_channel >= n)
        throw InputError(a.address_where, "output " + std::to_string(a.device_channel) + " of avar-device link '" +
                                              rig.links[link].name + "' is outside 0.." + std::to_string(n - 1) +
                                              ": a device's outputs are numbered from 0, one per channel it drives");
      const rig::ActuatorSpec*& slot = out[static_cast<std::size_t>(a.device_channel)];
      if (slot)
        throw InputError(a.address_where, "output " + std::to_string(a.device_channel) + " of avar-device link '" +
                                              rig.links[link].name + "' is given twice");
      slot = &a;
    }
  return out;
}

sim::SimAvarDeviceConfig device_config(const rig::Rig& rig, std::size_t link) {
  const auto& o = rig.links[link].options_as<rig::AvarDeviceOptions>();
  sim::SimAvarDeviceConfig config;
  config.baud = rig.links[link].baud;
  config.rate_hz = static_cast<std::uint16_t>(o.device_rate_hz);
  config.knot_capacity = static_cast<std::uint8_t>(o.device_knots);
  config.watchdog_ms = static_cast<std::uint32_t>(o.device_watchdog_ms);
  for (const rig::ActuatorSpec* a : by_output(rig, link)) {
    const rig::ChannelSpec& ch = rig.channel(a->channel);
    sim::SimAvarDeviceChannel c;
    c.limits =
        device::streaming_limits({ch.min, ch.max}, ch.rest, ch.max_velocity, ch.max_acceleration, ch.soft_margin, config.rate_hz);
    c.pulse_at_low_us = a->calibration.to_device(ch.min);
    c.pulse_at_high_us = a->calibration.to_device(ch.max);
    config.channels.push_back(c);
  }
  return config;
}

SimulatedDevice simulated_avar_device(const rig::Rig& rig, std::size_t link) {
  auto device = std::make_unique<sim::SimAvarDevice>(device_config(rig, link));
  sim::SimAvarDevice* d = device.get();
  return {std::move(device), [d](const rig::ActuatorSpec& a) {
            return a.calibration.to_channel(d->servo_position_us(static_cast<std::size_t>(a.device_channel)));
          }};
}

/// `avar sim avar-device`: a device of --channels hobby servos (0..100 % over 1000..2000 µs, rest
/// 50 %, 300 %/s, 3000 %/s²), as a board flashed with avar's streaming player would be.
ServedDevice standalone_avar_device(const SimValues& values) {
  const long long channels = values.integer("channels"), rate = values.integer("rate"), knots = values.integer("knots"),
                  watchdog = values.integer("watchdog-ms");
  if (channels < 1 || channels > firmware_iface::avar_device::kMaxChannels)
    throw SimOptionError("--channels: expected 1 to " + std::to_string(firmware_iface::avar_device::kMaxChannels) + ", found " +
                         std::to_string(channels));
  if (rate < 1 || rate > 10000)
    throw SimOptionError("--rate: expected 1 to 10000 control ticks per second, found " + std::to_string(rate));
  if (knots < 2 || knots > 255) throw SimOptionError("--knots: expected 2 to 255 knot frames, found " + std::to_string(knots));
  if (watchdog < 0 || watchdog > 60000)
    throw SimOptionError("--watchdog-ms: expected 0 to 60000, found " + std::to_string(watchdog));
  sim::SimAvarDeviceConfig config;
  config.rate_hz = static_cast<std::uint16_t>(rate);
  config.knot_capacity = static_cast<std::uint8_t>(knots);
  config.watchdog_ms = static_cast<std::uint32_t>(watchdog);
  for (long long c = 0; c < channels; ++c) {
    sim::SimAvarDeviceChannel ch;
    ch.limits = device::streaming_limits({0, 100}, 50, 300, 3000, 0, config.rate_hz);
    config.channels.push_back(ch);
  }
  auto device = std::make_unique<sim::SimAvarDevice>(config);
  const sim::SimAvarDevice* d = device.get();
  ServedDevice out;
  out.description = "simulated avar-device (" + std::to_string(channels) + " channels at " + std::to_string(rate) + " Hz, " +
                    std::to_string(knots) + " knots ahead)";
  out.state = [d] {
    static const char* const states[] = {"resting", "streaming", "stopping", "released"};
    const std::uint8_t s = d->player().state;
    std::string line = std::string(s < 4 ? states[s] : "?") + ", pulses (µs):";
    for (std::size_t c = 0; c < d->channel_count() && c < 12; ++c) line += " " + std::to_string(std::lround(d->pulse_us(c)));
    return line;
  };
  out.device = std::move(device);
  return out;
}

}  // namespace

firmware_iface::AvarDeviceLinkConfig avar_device_config(const rig::Rig& rig, std::size_t link, const DriverTuning& tuning) {
  const auto& o = rig.links[link].options_as<rig::AvarDeviceOptions>();
  firmware_iface::AvarDeviceLinkConfig config;
  config.baud = rig.links[link].baud;
  config.tick = std::chrono::microseconds(std::max(1L, std::lround(1e6 / rig.rate_hz)));
  config.knot_every = static_cast<int>(std::max(1L, std::lround(o.knot_ms * rig.rate_hz / 1000.0)));
  const auto spacing = config.tick * config.knot_every;
  config.lead = std::max(std::chrono::microseconds(1000L * o.lead_ms), 2 * spacing + config.tick);
  config.reply_timeout = tuning.reply_timeout(std::chrono::milliseconds(100));
  for (const rig::ActuatorSpec* a : by_output(rig, link)) {
    const rig::ChannelSpec& ch = rig.channel(a->channel);
    firmware_iface::AvarDeviceActuator actuator;
    actuator.channel = a->channel.value;
    actuator.device_channel = a->device_channel;
    // Output units over the channel's range; the device maps them to its pulses itself.
    actuator.calibration = {ch.min, ch.max, 0, 65535, false, 0};
    config.actuators.push_back(actuator);
  }
  return config;
}

const Protocol& avar_device_protocol() {
  static const Protocol p{
      .name = "avar-device",
      .open =
          [](const rig::Rig& figure, std::size_t index, LinkEndpoint at) {
            return open_over_bytes(figure, index, at,
                                   [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
                                      const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
                                     return std::make_unique<firmware_iface::AvarDeviceLink>(
                                         transport, avar_device_config(rig, link, tuning));
                                   });
          },
      .make_simulated = simulated_avar_device,
      .sim =
          {
              .name = "avar-device",
              .alias = nullptr,
              .summary = "A board running avar's streaming player (curve knots over serial, played on the device)",
              .description =
                  "A microcontroller running avar's streaming player (the same source a board runs, built for this "
                  "machine): it takes curve knots and avar's clock over the serial line, plays the cubic between knots at "
                  "its own control rate through its own limiter, eases to rest when the link goes silent for its watchdog "
                  "time, and drives hobby servos (0..100 % over 1000..2000 µs). See the avar-device protocol page.",
              .transport = SimTransport::pty,
              .example = "  avar sim avar-device --channels 8          # prints /dev/pts/N\n"
                         "  avar play SHOW.yaml --rig RIG.yaml --port /dev/pts/N    # a rig whose link says avar-device: {}",
              .options = {{"channels", "8", "Channels the device drives (1..61)"},
                          {"rate", "200", "The device's control ticks per second"},
                          {"knots", "16", "Knot frames the device holds ahead"},
                          {"watchdog-ms", "500", "Link silence (ms) after which the device eases to rest; 0: never"}},
              .make = standalone_avar_device,
          },
  };
  return p;
}

}  // namespace avar::assembly
