#include "avar/figure_links.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "avar/control/threaded_link.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_dmx.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_feetech.hpp"
#include "avar/sim/sim_ssc32.hpp"
#include "avar/sim/sim_maestro.hpp"

namespace avar::app {

firmware_iface::MaestroLinkConfig maestro_config(const control::Rig& rig, std::size_t link) {
  const control::LinkSpec& spec = rig.links[link];
  firmware_iface::MaestroLinkConfig config;
  config.framing.pololu = spec.maestro.pololu_form;
  config.framing.device_number = spec.maestro.device_number;
  config.framing.crc = spec.maestro.crc;
  config.channel_count = spec.maestro.channel_count;
  config.baud_detect = spec.maestro.baud_detect;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    firmware_iface::MaestroActuator m{a.channel, a.device_channel, a.calibration, {}, {}};
    // Device-side limits are given in channel units; the Maestro counts in pulse width.
    if (a.speed_limit) m.speed_us_per_s = *a.speed_limit * a.calibration.device_per_unit();
    if (a.acceleration_limit) m.acceleration_us_per_s2 = *a.acceleration_limit * a.calibration.device_per_unit();
    config.actuators.push_back(m);
  }
  return config;
}

firmware_iface::DynamixelLinkConfig dynamixel_config(const control::Rig& rig, std::size_t link) {
  const control::LinkSpec& spec = rig.links[link];
  firmware_iface::DynamixelLinkConfig config;
  switch (spec.bus.readback) {
    case control::Readback::none: config.readback = firmware_iface::DynamixelReadback::none; break;
    case control::Readback::position: config.readback = firmware_iface::DynamixelReadback::position; break;
    case control::Readback::full: config.readback = firmware_iface::DynamixelReadback::full; break;
  }
  config.reply_timeout = std::chrono::milliseconds(spec.bus.reply_timeout_ms);
  config.retries = static_cast<std::uint32_t>(spec.bus.retries);
  // The watchdog decides when silence is a fault: a servo may miss that many exchanges.
  config.silent_exchanges = std::max<std::uint32_t>(2, static_cast<std::uint32_t>(std::ceil(spec.watchdog_s * rig.rate_hz)));
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    firmware_iface::DynamixelActuator d;
    d.channel = a.channel;
    d.id = static_cast<std::uint8_t>(a.device_channel);
    d.calibration = a.calibration;
    d.speed_limit = a.speed_limit;
    d.acceleration_limit = a.acceleration_limit;
    config.actuators.push_back(d);
  }
  return config;
}

firmware_iface::FeetechLinkConfig feetech_config(const control::Rig& rig, std::size_t link) {
  const control::LinkSpec& spec = rig.links[link];
  firmware_iface::FeetechLinkConfig config;
  config.series = spec.bus.scs ? firmware_iface::feetech::Series::scs : firmware_iface::feetech::Series::sts;
  config.baud = spec.baud;
  switch (spec.bus.readback) {
    case control::Readback::none: config.readback = firmware_iface::FeetechReadback::none; break;
    case control::Readback::position: config.readback = firmware_iface::FeetechReadback::position; break;
    case control::Readback::full: config.readback = firmware_iface::FeetechReadback::full; break;
  }
  config.reply_timeout = std::chrono::milliseconds(spec.bus.reply_timeout_ms);
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    firmware_iface::FeetechActuator f;
    f.channel = a.channel;
    f.id = static_cast<std::uint8_t>(a.device_channel);
    f.calibration = a.calibration;
    // Device-side limits are given in channel units; the servo counts in position steps.
    if (a.speed_limit) f.speed_steps_per_s = *a.speed_limit * a.calibration.device_per_unit();
    if (a.acceleration_limit) f.acceleration_steps_per_s2 = *a.acceleration_limit * a.calibration.device_per_unit();
    config.actuators.push_back(f);
  }
  return config;
}

firmware_iface::Ssc32LinkConfig ssc32_config(const control::Rig& rig, std::size_t link) {
  firmware_iface::Ssc32LinkConfig config;
  config.baud = rig.links[link].baud;
  // Each group move lasts one tick, so the servos glide between the ticks' positions.
  config.move_time = std::chrono::milliseconds(static_cast<long>(std::lround(1000.0 / rig.rate_hz)));
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    firmware_iface::Ssc32Actuator s;
    s.channel = a.channel;
    s.device_channel = a.device_channel;
    s.calibration = a.calibration;
    if (a.speed_limit) s.speed_us_per_s = *a.speed_limit * a.calibration.device_per_unit();
    config.actuators.push_back(s);
  }
  return config;
}

firmware_iface::DmxLinkConfig dmx_config(const control::Rig& rig, std::size_t link) {
  firmware_iface::DmxLinkConfig config;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    firmware_iface::DmxActuator d;
    d.channel = a.channel;
    d.address = a.device_channel;
    d.fine = a.fine;
    d.calibration = a.calibration;
    config.actuators.push_back(d);
  }
  return config;
}

struct FigureLinks::Entry {
  std::size_t link_index = 0;
  bool simulated = false;
  std::unique_ptr<sim::ByteDevice> device;
  /// The simulated device's true position of an actuator, in channel units (ground truth).
  std::function<double(const control::ActuatorSpec&)> true_position;
  std::unique_ptr<sim::PtyDeviceHost> host;
  std::unique_ptr<firmware_iface::SerialTransport> transport;
  std::unique_ptr<firmware_iface::ActuatorLink> link;
  std::unique_ptr<control::ThreadedLink> threaded;  ///< serves `link` from its own thread, when asked
  firmware_iface::ActuatorLink* outer() const {
    return threaded ? static_cast<firmware_iface::ActuatorLink*>(threaded.get()) : link.get();
  }
};

namespace {

/// A simulated Maestro set up as its owner would have set up the real one: the rig's channel
/// count, framing and CRC, each used channel's pulse range opened to the actuator's window, and
/// every servo parked at its rest pose (where the last soft stop left it).
sim::SimMaestroConfig simulated_maestro(const control::Rig& rig, std::size_t link) {
  const control::LinkSpec& spec = rig.links[link];
  sim::SimMaestroConfig config;
  config.channel_count = spec.maestro.channel_count;
  config.device_number = spec.maestro.device_number;
  config.crc = spec.maestro.crc;
  config.baud_detect = spec.maestro.baud_detect;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    auto& ch = config.channels[static_cast<std::size_t>(a.device_channel)];
    ch.min_us = a.calibration.device_low();
    ch.max_us = a.calibration.device_high();
    ch.initial_position_us = a.calibration.to_device(rig.channels[a.channel].rest);
  }
  return config;
}

/// Simulated DYNAMIXEL servos with the rig's IDs, each parked at its rest pose.
sim::SimDynamixelConfig simulated_dynamixel(const control::Rig& rig, std::size_t link) {
  sim::SimDynamixelConfig config;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    sim::SimDynamixelServo servo;
    servo.id = static_cast<std::uint8_t>(a.device_channel);
    servo.initial_position = static_cast<std::int32_t>(std::lround(a.calibration.to_device(rig.channels[a.channel].rest)));
    config.servos.push_back(servo);
  }
  return config;
}

/// Simulated Feetech servos with the rig's IDs and series, each parked at its rest pose.
sim::SimFeetechConfig simulated_feetech(const control::Rig& rig, std::size_t link) {
  sim::SimFeetechConfig config;
  config.series = rig.links[link].bus.scs ? firmware_iface::feetech::Series::scs : firmware_iface::feetech::Series::sts;
  config.baud = rig.links[link].baud;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    sim::SimFeetechServo servo;
    servo.id = static_cast<std::uint8_t>(a.device_channel);
    servo.initial_position = std::round(a.calibration.to_device(rig.channels[a.channel].rest));
    config.servos.push_back(servo);
  }
  return config;
}

/// A simulated DMX widget with a servo decoder (or dimmer) on every actuator's slots.
sim::SimDmxConfig simulated_dmx(const control::Rig& rig, std::size_t link) {
  sim::SimDmxConfig config;
  config.baud = rig.links[link].baud;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (a.link != link) continue;
    sim::SimDmxFixture fixture;
    fixture.address = a.device_channel;
    fixture.fine = a.fine;
    config.fixtures.push_back(fixture);
  }
  return config;
}

/// Index of an actuator among its link's actuators (the order simulated devices list them in).
std::size_t index_on_link(const control::Rig& rig, const control::ActuatorSpec& wanted) {
  std::size_t i = 0;
  for (const control::ActuatorSpec& a : rig.actuators) {
    if (&a == &wanted) return i;
    if (a.link == wanted.link) ++i;
  }
  return i;
}

/// The simulated device of a link, and how to read an actuator's true position off it.
void make_simulated_device(const control::Rig& rig, std::size_t link, FigureLinks::Entry& e);

}  // namespace

FigureLinks::FigureLinks(const control::Rig& rig, const LinkSelection& selection) : rig_(rig) {
  if (selection.port && rig.links.size() != 1)
    throw InputError({rig.file, rig.links[0].where.line, rig.links[0].where.column},
                     "--port sets the port of a rig's single link, but this rig has " + std::to_string(rig.links.size()) +
                         " links; set each link's port in the rig file");
  for (std::size_t i = 0; i < rig.links.size(); ++i) {
    auto entry = std::make_unique<Entry>();
    entry->link_index = i;
    std::string port = selection.port.value_or(rig.links[i].port);
    entry->simulated = selection.simulate_all || port == "sim";
    if (entry->simulated) {
      make_simulated_device(rig, i, *entry);
      entry->host = std::make_unique<sim::PtyDeviceHost>(*entry->device, sim::PtyDeviceHost::Clock::stepped);
      port = entry->host->slave_path();
    }
    entry->transport = std::make_unique<firmware_iface::SerialTransport>(port, rig.links[i].baud);
    if (entry->simulated) {
      // A simulated device answers from a thread of this process, which a busy machine may keep
      // waiting for longer than a real servo's reply timeout (200 ms was once not enough on a
      // saturated 2-core machine under the sanitizers): give it a second (it answers at once
      // when it runs, so only a lost reply would ever wait this long).
      control::Rig patched = rig;  // the drivers copy what they need from it
      patched.links[i].bus.reply_timeout_ms = std::max(patched.links[i].bus.reply_timeout_ms, 1000);
      entry->link = make_link(patched, i, *entry->transport);
    } else {
      entry->link = make_link(rig, i, *entry->transport);
    }
    if (selection.threaded_rate_hz > 0) {
      const auto watchdog_ticks = static_cast<std::uint32_t>(std::ceil(rig.links[i].watchdog_s * selection.threaded_rate_hz));
      entry->threaded = std::make_unique<control::ThreadedLink>(*entry->link, rig.channels.size(), watchdog_ticks);
    }
    entries_.push_back(std::move(entry));
  }
}

namespace {

void make_simulated_device(const control::Rig& rig, std::size_t link, FigureLinks::Entry& e) {
  switch (rig.links[link].protocol) {
    case control::Protocol::maestro: {
      auto device = std::make_unique<sim::SimMaestro>(simulated_maestro(rig, link));
      sim::SimMaestro* d = device.get();
      e.true_position = [d](const control::ActuatorSpec& a) {
        return a.calibration.to_channel(d->servo_position_us(a.device_channel));
      };
      e.device = std::move(device);
      return;
    }
    case control::Protocol::dynamixel: {
      auto device = std::make_unique<sim::SimDynamixel>(simulated_dynamixel(rig, link));
      sim::SimDynamixel* d = device.get();
      e.true_position = [d, &rig](const control::ActuatorSpec& a) {
        return a.calibration.to_channel(d->position(index_on_link(rig, a)));
      };
      e.device = std::move(device);
      return;
    }
    case control::Protocol::feetech: {
      auto device = std::make_unique<sim::SimFeetech>(simulated_feetech(rig, link));
      sim::SimFeetech* d = device.get();
      e.true_position = [d, &rig](const control::ActuatorSpec& a) {
        return a.calibration.to_channel(d->position(index_on_link(rig, a)));
      };
      e.device = std::move(device);
      return;
    }
    case control::Protocol::ssc32: {
      sim::SimSsc32Config config;
      config.baud = rig.links[link].baud;
      auto device = std::make_unique<sim::SimSsc32>(config);
      sim::SimSsc32* d = device.get();
      e.true_position = [d](const control::ActuatorSpec& a) {
        return a.calibration.to_channel(d->servo_position_us(a.device_channel));
      };
      e.device = std::move(device);
      return;
    }
    case control::Protocol::dmx: {
      auto device = std::make_unique<sim::SimDmx>(simulated_dmx(rig, link));
      sim::SimDmx* d = device.get();
      // A dimmer's truth is the level the widget puts out.
      e.true_position = [d, &rig](const control::ActuatorSpec& a) {
        return a.calibration.to_channel(d->fixture_level(index_on_link(rig, a)));
      };
      e.device = std::move(device);
      return;
    }
  }
  throw InputError({rig.file, rig.links[link].where.line, rig.links[link].where.column},
                   std::string("unknown protocol ") + control::to_string(rig.links[link].protocol));
}

}  // namespace

std::unique_ptr<firmware_iface::ActuatorLink> make_link(const control::Rig& rig, std::size_t link,
                                                        firmware_iface::ByteTransport& transport) {
  switch (rig.links[link].protocol) {
    case control::Protocol::maestro: return std::make_unique<firmware_iface::MaestroLink>(transport, maestro_config(rig, link));
    case control::Protocol::dynamixel:
      return std::make_unique<firmware_iface::DynamixelLink>(transport, dynamixel_config(rig, link));
    case control::Protocol::feetech: return std::make_unique<firmware_iface::FeetechLink>(transport, feetech_config(rig, link));
    case control::Protocol::ssc32: return std::make_unique<firmware_iface::Ssc32Link>(transport, ssc32_config(rig, link));
    case control::Protocol::dmx: return std::make_unique<firmware_iface::DmxLink>(transport, dmx_config(rig, link));
  }
  throw InputError({rig.file, rig.links[link].where.line, rig.links[link].where.column},
                   std::string("unknown protocol ") + control::to_string(rig.links[link].protocol));
}

FigureLinks::~FigureLinks() {
  // Close the serial side before the simulated devices behind it go away.
  for (auto& e : entries_) {
    e->threaded.reset();
    e->link.reset();
    e->transport.reset();
  }
}

std::vector<firmware_iface::ActuatorLink*> FigureLinks::links() const {
  std::vector<firmware_iface::ActuatorLink*> out;
  for (const auto& e : entries_) out.push_back(e->outer());
  return out;
}

bool FigureLinks::any_simulated() const {
  for (const auto& e : entries_)
    if (e->simulated) return true;
  return false;
}

bool FigureLinks::all_simulated() const {
  for (const auto& e : entries_)
    if (!e->simulated) return false;
  return true;
}

std::string FigureLinks::describe(std::size_t link) const {
  const Entry& e = *entries_[link];
  return (e.simulated ? "simulated " : "") + e.link->describe();
}

firmware_iface::LinkCounters FigureLinks::counters(std::size_t link) const { return entries_[link]->outer()->counters(); }

bool FigureLinks::reports_telemetry(std::size_t link) const {
  const control::Protocol p = rig_.links[link].protocol;
  return (p == control::Protocol::dynamixel || p == control::Protocol::feetech) && rig_.links[link].bus.readback != control::Readback::none;
}

void FigureLinks::read_telemetry(std::span<firmware_iface::ChannelTelemetry> telemetry) const {
  for (const auto& e : entries_) e->outer()->read_telemetry(telemetry);
}

void FigureLinks::step_simulation(double dt_s, std::span<double> measured, std::span<bool> known) {
  for (const auto& e : entries_) {
    if (!e->simulated) continue;
    // Everything sent this tick must have reached the device before its time moves on, so
    // a run on the stepped clock is deterministic.
    e->host->wait_consumed(e->transport->bytes_written(), std::chrono::seconds(2));
    e->host->with_device([&](sim::ByteDevice& device) {
      device.advance(dt_s);
      for (const control::ActuatorSpec& a : rig_.actuators) {
        if (a.link != e->link_index) continue;
        measured[a.channel] = e->true_position(a);
        known[a.channel] = true;
      }
    });
  }
}

std::uint64_t FigureLinks::bytes_sent() const {
  std::uint64_t total = 0;
  for (const auto& e : entries_) total += e->transport->bytes_written();
  return total;
}

}  // namespace avar::app
