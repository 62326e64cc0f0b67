#include "avar/assembly/figure_links.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "avar/control/threaded_link.hpp"
#include "avar/firmware_iface/linux_i2c_bus.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/firmware_iface/sysfs_pwm_chip.hpp"
#include "avar/sim/sim_i2c_bus.hpp"
#include "avar/sim/sim_pwm_chip.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/usb_device_host.hpp"

namespace avar::assembly {

struct FigureLinks::Entry {
  std::size_t link_index = 0;
  bool simulated = false;
  SimulatedDevice device;
  std::unique_ptr<sim::PtyDeviceHost> host;                    ///< a simulated device behind a serial port
  std::unique_ptr<sim::UsbDeviceHost> usb_host;                ///< a simulated device on USB
  std::unique_ptr<firmware_iface::SerialTransport> transport;  ///< null for links that are no serial port
  std::shared_ptr<firmware_iface::GpioChip> chip;              ///< a gpio link's chip
  std::shared_ptr<firmware_iface::I2cBus> i2c;                 ///< an I2C link's bus
  std::shared_ptr<sim::SimI2cBus> sim_i2c;                     ///< the same, when simulated
  std::shared_ptr<firmware_iface::PwmChip> pwm;                ///< a pwm link's chip
  std::shared_ptr<sim::SimPwmChip> sim_pwm;                    ///< the same, when simulated
  std::unique_ptr<firmware_iface::ActuatorLink> link;
  std::unique_ptr<control::ThreadedLink> threaded;  ///< serves `link` from its own thread, when asked
  firmware_iface::ActuatorLink* outer() const {
    return threaded ? static_cast<firmware_iface::ActuatorLink*>(threaded.get()) : link.get();
  }
};

namespace {

/// A gpio link's chip (simulated for port sim or --sim), shared through the selection's chips.
std::shared_ptr<firmware_iface::GpioChip> open_chip(const rig::Rig& rig, std::size_t i, const std::string& port, bool simulated,
                                                    const LinkSelection& selection, std::shared_ptr<GpioChips>& chips) {
  if (!chips) chips = selection.gpio_chips ? selection.gpio_chips : std::make_shared<GpioChips>(selection.simulate_all);
  const rig::LinkSpec& spec = rig.links[i];
  try {
    return chips->open(port, simulated);
  } catch (const std::runtime_error& e) {
    throw InputError({rig.file, spec.where.line, spec.where.column}, "link '" + spec.name + "': " + e.what());
  }
}

}  // namespace

FigureLinks::FigureLinks(const rig::Rig& rig, const LinkSelection& selection)
    : rig_(rig), truth_(rig.channels.size(), 0.0), truth_known_(rig.channels.size(), 0) {
  if (selection.port && rig.links.size() != 1)
    throw InputError({rig.file, rig.links[0].where.line, rig.links[0].where.column},
                     "--port sets the port of a rig's single link, but this rig has " + std::to_string(rig.links.size()) +
                         " links; set each link's port in the rig file");
  for (std::size_t i = 0; i < rig.links.size(); ++i) {
    const Protocol& protocol = protocol_of(rig.links[i]);
    auto entry = std::make_unique<Entry>();
    entry->link_index = i;
    const std::string port = selection.port.value_or(rig.links[i].port);
    entry->simulated = selection.simulate_all || port == "sim";
    // Where the driver talks: the port, or the simulated device served here (a byte device on a
    // pseudo-terminal, a USB device in this process, a node on loopback, a simulated chip).
    LinkEndpoint at;
    at.port = port;
    if (protocol.on_gpio_chip) {
      entry->chip = open_chip(rig, i, port, entry->simulated, selection, gpio_chips_);
      at.chip = entry->chip;
    } else if (protocol.on_i2c_bus) {
      if (entry->simulated) {
        // The link's board, at its address, on a bus of its own.
        entry->sim_i2c = std::make_shared<sim::SimI2cBus>();
        entry->sim_i2c->add_pca9685(static_cast<std::uint8_t>(rig.links[i].options_as<rig::Pca9685Options>().address));
        entry->i2c = entry->sim_i2c;
      } else {
        try {
          entry->i2c = firmware_iface::open_i2c_bus(port);
        } catch (const std::runtime_error& e) {
          const rig::LinkSpec& spec = rig.links[i];
          throw InputError({rig.file, spec.where.line, spec.where.column}, "link '" + spec.name + "': " + e.what());
        }
      }
      at.i2c = entry->i2c;
    } else if (protocol.on_pwm_chip) {
      if (entry->simulated) {
        entry->sim_pwm = std::make_shared<sim::SimPwmChip>();
        entry->pwm = entry->sim_pwm;
      } else {
        try {
          entry->pwm = firmware_iface::open_pwm_chip(port);
        } catch (const std::runtime_error& e) {
          const rig::LinkSpec& spec = rig.links[i];
          throw InputError({rig.file, spec.where.line, spec.where.column}, "link '" + spec.name + "': " + e.what());
        }
      }
      at.pwm = entry->pwm;
    } else if (entry->simulated) {
      entry->device = protocol.make_simulated(rig, i);
      if (entry->device.network_node) {
        at.port = entry->device.network_node->endpoint();
      } else if (entry->device.usb_device) {
        entry->usb_host = std::make_unique<sim::UsbDeviceHost>(*entry->device.usb_device, entry->device.usb_name);
        at.usb = entry->usb_host->connect();
      } else {
        if (selection.prepare_simulated) selection.prepare_simulated(i, *entry->device.device);
        // Drives that need their own time to come up (a heartbeat) run on the wall clock until
        // the first tick; every other simulator waits for the loop's stepped clock from the start.
        const auto clock =
            protocol.simulation_runs_during_start ? sim::PtyDeviceHost::Clock::wall : sim::PtyDeviceHost::Clock::stepped;
        entry->host = std::make_unique<sim::PtyDeviceHost>(*entry->device.device, clock);
        at.port = entry->host->slave_path();
        at.simulated = true;
        // A simulated device answers from a thread of this process, which a busy machine may keep
        // waiting for longer than a real servo's reply timeout (200 ms was once not enough on a
        // saturated 2-core machine under the sanitizers): give it a second (it answers at once
        // when it runs, so only a lost reply would ever wait this long).
        at.tuning.min_reply_timeout_ms = 1000;
      }
    }
    OpenedLink opened = protocol.open(rig, i, std::move(at));
    entry->transport = std::move(opened.serial);
    entry->link = std::move(opened.driver);
    if (selection.threaded_rate_hz > 0) {
      const auto watchdog_ticks = static_cast<std::uint32_t>(std::ceil(rig.links[i].watchdog_s * selection.threaded_rate_hz));
      entry->threaded = std::make_unique<control::ThreadedLink>(*entry->link, rig.channels.size(), watchdog_ticks);
    }
    entries_.push_back(std::move(entry));
  }
}

FigureLinks::~FigureLinks() {
  // Close the serial side before the simulated devices behind it go away.
  for (auto& e : entries_) {
    e->threaded.reset();
    e->link.reset();
    e->transport.reset();
    e->usb_host.reset();
    e->chip.reset();
    e->i2c.reset();
    e->pwm.reset();
  }
}

std::vector<firmware_iface::ActuatorLink*> FigureLinks::links() const {
  std::vector<firmware_iface::ActuatorLink*> out;
  for (const auto& e : entries_) out.push_back(e->outer());
  return out;
}

bool FigureLinks::any_simulated() const {
  return std::any_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->simulated; });
}

bool FigureLinks::all_simulated() const {
  return std::all_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->simulated; });
}

std::string FigureLinks::describe(std::size_t link) const {
  const Entry& e = *entries_[link];
  // (A simulated chip or I2C bus says so itself.)
  return (e.simulated && !e.chip && !e.i2c && !e.pwm ? "simulated " : "") + e.link->describe();
}

sim::SimDmxNode* FigureLinks::simulated_node(std::size_t link) const { return entries_.at(link)->device.network_node.get(); }

firmware_iface::LinkCounters FigureLinks::counters(std::size_t link) const { return entries_[link]->outer()->counters(); }

bool FigureLinks::reports_telemetry(std::size_t link) const {
  return rig::schema_of(rig_.links[link]).reports_telemetry(rig_.links[link]);
}

void FigureLinks::with_simulated(std::size_t link, const std::function<void(sim::ByteDevice&)>& f) {
  const Entry& e = *entries_.at(link);
  if (!e.host) throw std::invalid_argument("link " + std::to_string(link) + " is not simulated behind a serial port");
  e.host->with_device([&](sim::ByteDevice& d) { f(d); });
}

void FigureLinks::with_simulated_usb(std::size_t link, const std::function<void(sim::UsbDeviceHost&)>& f) {
  const Entry& e = *entries_.at(link);
  if (!e.usb_host) throw std::invalid_argument("link " + std::to_string(link) + " is not simulated on USB");
  f(*e.usb_host);
}

std::string FigureLinks::channel_problem(std::size_t channel) const {
  for (const rig::ActuatorSpec& a : rig_.actuators)
    if (a.channel.value == channel)
      if (std::string p = entries_[a.link.value]->link->channel_problem(channel); !p.empty()) return p;
  return {};
}

void FigureLinks::advance(double dt_s) {
  for (const auto& e : entries_) {
    if (!e->simulated) continue;
    if (e->sim_i2c) {
      // A simulated board's outputs change as they are written: read each one's pulse.
      const auto& o = rig_.links[e->link_index].options_as<rig::Pca9685Options>();
      for (const rig::ActuatorSpec& a : rig_.actuators_on(rig::LinkIndex{e->link_index})) {
        const double pulse =
            e->sim_i2c->pulse_us(static_cast<std::uint8_t>(o.address), static_cast<std::uint8_t>(a.device_channel),
                                 static_cast<std::uint32_t>(o.clock_hz));
        if (pulse <= 0) continue;  // no pulse: a limp servo stays where it is
        truth_[a.channel.value] = a.calibration.to_channel(pulse);
        truth_known_[a.channel.value] = 1;
      }
      continue;
    }
    if (e->sim_pwm) {
      // A simulated PWM chip's outputs change as they are set: read each one's pulse.
      for (const rig::ActuatorSpec& a : rig_.actuators_on(rig::LinkIndex{e->link_index})) {
        const double pulse = e->sim_pwm->pulse_us(static_cast<unsigned>(a.device_channel));
        if (pulse <= 0) continue;  // no pulse: a limp servo stays where it is
        truth_[a.channel.value] = a.calibration.to_channel(pulse);
        truth_known_[a.channel.value] = 1;
      }
      continue;
    }
    if (e->chip) {
      // A simulated chip's lines change as they are set: read what each output drives.
      for (const rig::ActuatorSpec& a : rig_.actuators_on(rig::LinkIndex{e->link_index})) {
        bool on = false;
        if (e->chip->get(static_cast<unsigned>(a.device_channel), on) != Status::ok) continue;
        truth_[a.channel.value] = a.calibration.to_channel(on ? 1.0 : 0.0);
        truth_known_[a.channel.value] = 1;
      }
      continue;
    }
    const auto step = [&](auto& device) {
      device.advance(dt_s);
      for (const rig::ActuatorSpec& a : rig_.actuators_on(rig::LinkIndex{e->link_index})) {
        truth_[a.channel.value] = e->device.true_position(a);
        truth_known_[a.channel.value] = 1;
      }
    };
    if (e->device.network_node) {
      // Everything sent so far must have reached the node before its time moves on.
      e->device.network_node->receive_until(e->link->counters().bytes_sent, std::chrono::seconds(2));
      for (const rig::ActuatorSpec& a : rig_.actuators_on(rig::LinkIndex{e->link_index})) {
        truth_[a.channel.value] = e->device.true_position(a);
        truth_known_[a.channel.value] = 1;
      }
      continue;
    }
    if (e->usb_host) {
      // Control transfers are answered as they are made: nothing is in flight.
      e->usb_host->with_device(step);
      continue;
    }
    e->host->set_clock(sim::PtyDeviceHost::Clock::stepped);
    // Everything sent this tick must have reached the device before its time moves on, so
    // a run on the stepped clock is deterministic.
    e->host->wait_consumed(e->transport->bytes_written(), std::chrono::seconds(2));
    e->host->with_device(step);
  }
}

void FigureLinks::measure(std::span<double> measured, std::span<bool> known) const noexcept {
  for (std::size_t c = 0; c < truth_.size() && c < measured.size(); ++c) {
    if (!truth_known_[c]) continue;
    measured[c] = truth_[c];
    known[c] = true;
  }
}

std::uint64_t FigureLinks::bytes_sent() const {
  std::uint64_t total = 0;
  for (const auto& e : entries_) total += e->transport ? e->transport->bytes_written() : e->outer()->counters().bytes_sent;
  return total;
}

}  // namespace avar::assembly
