#pragma once
// One cell of the fault matrix: a protocol's small rig assembled through the protocol registry
// (the real driver and its real transport code) against the protocol's simulated device, a
// short show played on the stepped clock, the fault injected partway through the show for
// kFaultWindowS and then lifted. Everything the cell's verdict needs is collected here; the
// test asserts it.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/assembly/protocol.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/faulty_device.hpp"
#include "avar/sim/faulty_usb_device.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_wire.hpp"
#include "avar/sim/usb_device_host.hpp"
#include "fault_cases.hpp"
#include "faulty_datagram_path.hpp"

namespace avar::fault_matrix {

inline constexpr double kFaultOnsetShowS = 0.4;  ///< show time at which the fault begins
inline constexpr double kFaultWindowS = 0.5;     ///< how long it lasts (longer than the watchdog)
inline constexpr double kUsbHostTimeoutS = 0.1;  ///< the Maestro USB link's transfer timeout

/// What one cell's run showed.
struct CellRun {
  bool started = false;
  std::string problem;     ///< why the run could not be made, for the message
  control::Fault fault;    ///< the latched fault (cause none: the show ran through)
  bool link_dead = false;  ///< the controller stopped sending to the link
  control::Phase end_phase = control::Phase::disabled;
  double show_time_reached = 0;
  double show_end = 0;
  double onset_s = -1, lifted_s = -1;  ///< loop time the fault began and was lifted
  double watchdog_s = 0;               ///< the link's watchdog (CAN: the heartbeat timeout too)
  double tick_s = 0;
  std::vector<double> final_command;  ///< per channel, the last frame the controller sent
  std::vector<double> rest;
  double worst_excursion = 0;  ///< channel units beyond [min, max] the device ever stood at
  std::string worst_where;
  firmware_iface::LinkCounters before, after;  ///< the link's counters at onset and at the end
  sim::FaultCounts injected;                   ///< what the injector did
  std::uint64_t node_out_of_order = 0;         ///< network nodes only: packets refused by sequence
  std::uint64_t node_packets_in_window = 0;    ///< network nodes only: packets taken while the fault lasted
  std::uint64_t reconnects_after_replug = 0;   ///< disconnect: reopens once the wire came back
  bool resent_after_replug = false;
};

/// Plays one cell.
inline CellRun run_cell(const ProtocolCase& pc, FaultKind kind, std::uint64_t seed);

namespace cell_detail {

inline playback::Show fault_matrix_show() {
  playback::Show s;
  s.name = "fault-matrix";
  s.duration = 2.0;
  const std::array<std::pair<double, double>, 5> keys_a{{{0.0, 0.0}, {0.5, 40.0}, {1.0, -40.0}, {1.5, 30.0}, {2.0, 0.0}}};
  const std::array<std::pair<double, double>, 5> keys_b{{{0.0, 10.0}, {0.5, -40.0}, {1.0, 40.0}, {1.5, -20.0}, {2.0, 0.0}}};
  for (const auto* keys : {&keys_a, &keys_b}) {
    playback::RawCurve raw;
    for (const auto& [t, v] : *keys) {
      playback::RawKey k;
      k.time = t;
      k.value = v;
      raw.keys.push_back(k);
    }
    playback::Curve curve = playback::Curve::build(raw);
    s.tracks.push_back({keys == &keys_a ? "a" : "b", raw, std::move(curve), {}});
  }
  return s;
}

inline sim::FaultPlan plan_for(FaultKind kind, Carrier carrier, std::uint64_t seed) {
  sim::FaultPlan p;
  p.seed = seed;
  switch (kind) {
    case FaultKind::drop: p.drop_command = 0.3; break;
    case FaultKind::corrupt: p.corrupt_reply = 0.5; break;
    case FaultKind::truncate: p.truncate_reply = 0.5; break;
    case FaultKind::delay:  // past the reply timeout: 5..10 ms on the serial buses, 100 ms per USB transfer
      p.delay_reply_s = carrier == Carrier::usb ? 2 * kUsbHostTimeoutS : 0.05;
      break;
    case FaultKind::duplicate: p.duplicate_reply = 0.5; break;
    case FaultKind::reorder: p.reorder_reply = 0.5; break;
    case FaultKind::silent: p.silent = true; break;
    case FaultKind::garbage: p.garbage = true; break;
    case FaultKind::disconnect: break;  // the wire itself, not the plan
  }
  return p;
}

/// The driver of the rig's link over a byte transport of the test's, through the protocol's one way to open a link.
inline std::unique_ptr<firmware_iface::ActuatorLink> open_over(const assembly::Protocol& protocol, const rig::Rig& rig,
                                                               firmware_iface::ByteTransport* bytes) {
  assembly::LinkEndpoint at;
  at.bytes = bytes;
  return protocol.open(rig, 0, std::move(at)).driver;
}

/// The same over a USB device.
inline std::unique_ptr<firmware_iface::ActuatorLink> open_on_usb(const assembly::Protocol& protocol, const rig::Rig& rig,
                                                                 std::unique_ptr<firmware_iface::UsbControlTransport> usb) {
  assembly::LinkEndpoint at;
  at.usb = std::move(usb);
  return protocol.open(rig, 0, std::move(at)).driver;
}

/// The same at a network endpoint (HOST:PORT).
inline std::unique_ptr<firmware_iface::ActuatorLink> open_at(const assembly::Protocol& protocol, const rig::Rig& rig,
                                                             const std::string& port) {
  assembly::LinkEndpoint at;
  at.port = port;
  return protocol.open(rig, 0, std::move(at)).driver;
}

/// The figure under test: the device behind its fault injector and carrier, and the link.
class Figure final : public control::Plant, public control::TickObserver {
 public:
  Figure(const rig::Rig& rig, const ProtocolCase& pc, FaultKind kind, std::uint64_t seed, CellRun& out)
      : rig_(rig), pc_(pc), kind_(kind), seed_(seed), out_(out) {
    if (pc.carrier == Carrier::none) throw std::invalid_argument(std::string(pc.name) + ": no wire to put faults on");
    const assembly::Protocol& protocol = assembly::protocol_of(rig.links[0]);
    device_ = protocol.make_simulated(rig, 0);
    switch (pc.carrier) {
      case Carrier::serial:
        faulty_ = std::make_unique<sim::FaultyDevice>(*device_.device, sim::FaultPlan{});
        wire_ = std::make_unique<sim::SimWire>(*faulty_, rig.links[0].baud, 0, "simulated wire");
        link_ = open_over(protocol, rig, wire_.get());
        break;
      case Carrier::pty:
        faulty_ = std::make_unique<sim::FaultyDevice>(*device_.device, sim::FaultPlan{});
        pty_ = std::make_unique<sim::PtyDeviceHost>(*faulty_, sim::PtyDeviceHost::Clock::stepped);
        serial_ = std::make_unique<firmware_iface::SerialTransport>(pty_->slave_path(), rig.links[0].baud);
        link_ = open_over(protocol, rig, serial_.get());
        break;
      case Carrier::usb:
        faulty_usb_ = std::make_unique<sim::FaultyUsbDevice>(*device_.usb_device, sim::FaultPlan{}, kUsbHostTimeoutS);
        usb_host_ = std::make_unique<sim::UsbDeviceHost>(*faulty_usb_, device_.usb_name);
        link_ = open_on_usb(protocol, rig, usb_host_->connect());
        break;
      case Carrier::network:
        path_ = std::make_unique<FaultyDatagramPath>();
        link_ = open_at(protocol, rig, path_->endpoint());
        break;
      case Carrier::none: break;
    }
  }

  firmware_iface::ActuatorLink& link() { return *link_; }

  /// After every tick: the device moves by the tick, and where it stands is checked.
  void advance(double dt_s) override {
    switch (pc_.carrier) {
      case Carrier::serial: faulty_->advance(dt_s); break;
      case Carrier::pty:
        // Stepped time: the device first takes in everything sent, then moves by the tick.
        (void)pty_->wait_consumed(serial_->bytes_written(), std::chrono::seconds(2));
        break;
      case Carrier::usb: usb_host_->with_device([&](sim::UsbControlDevice& d) { d.advance(dt_s); }); break;
      case Carrier::network: {
        const std::uint64_t before = device_.network_node->counters().packets;
        path_->advance(dt_s, *device_.network_node);
        if (injecting_) out_.node_packets_in_window += device_.network_node->counters().packets - before;
        break;
      }
      case Carrier::none: break;
    }
    on_device([&] {
      if (pc_.carrier == Carrier::pty) faulty_->advance(dt_s);
      check_device_within_limits();
    });
  }

  void after_tick(std::uint64_t, double now_s, double, double, control::Controller& controller) override {
    if (out_.onset_s < 0 && controller.phase() == control::Phase::running && controller.show_time() >= kFaultOnsetShowS) {
      out_.onset_s = now_s;
      out_.before = link_->counters();
      set_fault(true);
    } else if (injecting_ && now_s >= out_.onset_s + kFaultWindowS) {
      out_.lifted_s = now_s;
      set_fault(false);
    }
  }

  /// After the run: the injector's account, and for a disconnect whether the link comes back.
  void finish(control::Controller& controller) {
    if (injecting_) set_fault(false);
    out_.after = link_->counters();
    if (faulty_) on_device([&] { out_.injected = faulty_->counts(); });
    if (faulty_usb_) out_.injected = faulty_usb_->counts();
    if (path_) out_.injected = path_->counts();
    if (device_.network_node) out_.node_out_of_order = device_.network_node->counters().out_of_order;
    if (kind_ != FaultKind::disconnect) return;
    // The wire is back: the link reopens it within its reconnect interval.
    const std::uint64_t reconnects = link_->counters().reconnects;
    const std::vector<double> rest = rig_.rest_frame();
    for (int i = 0; i < 30 && !out_.resent_after_replug; ++i) {
      out_.resent_after_replug = link_->send(rest) == Status::ok;
      advance(controller.tick_period());
    }
    out_.reconnects_after_replug = link_->counters().reconnects - reconnects;
  }

 private:
  void set_fault(bool on) {
    injecting_ = on;
    const sim::FaultPlan plan = on ? plan_for(kind_, pc_.carrier, seed_) : sim::FaultPlan{};
    if (faulty_) on_device([&] { faulty_->set_plan(plan); });
    if (faulty_usb_) faulty_usb_->set_plan(plan);
    if (path_) path_->set_plan(plan);
    if (kind_ != FaultKind::disconnect) return;
    if (wire_) wire_->set_connected(!on);
    if (usb_host_) usb_host_->set_plugged(!on);
    if (path_) path_->set_connected(!on);
  }

  /// Runs f with the device to itself (under its pseudo-terminal host's lock where it has one).
  template <class F>
  void on_device(F&& f) {
    if (pty_) pty_->with_device([&](sim::ByteDevice&) { f(); });
    else f();
  }

  void check_device_within_limits() {
    for (const rig::ActuatorSpec& a : rig_.actuators) {
      const rig::ChannelSpec& c = rig_.channel(a.channel);
      const double p = device_.true_position(a);
      const double beyond = std::isfinite(p) ? std::max({0.0, c.min - p, p - c.max}) : INFINITY;
      if (beyond > out_.worst_excursion) {
        out_.worst_excursion = beyond;
        out_.worst_where = "channel " + c.name + " at " + std::to_string(p);
      }
    }
  }

  const rig::Rig& rig_;
  const ProtocolCase& pc_;
  FaultKind kind_;
  std::uint64_t seed_;
  CellRun& out_;
  assembly::SimulatedDevice device_;
  std::unique_ptr<sim::FaultyDevice> faulty_;
  std::unique_ptr<sim::SimWire> wire_;
  std::unique_ptr<sim::PtyDeviceHost> pty_;
  std::unique_ptr<firmware_iface::SerialTransport> serial_;
  std::unique_ptr<sim::FaultyUsbDevice> faulty_usb_;
  std::unique_ptr<sim::UsbDeviceHost> usb_host_;
  std::unique_ptr<FaultyDatagramPath> path_;
  std::unique_ptr<firmware_iface::ActuatorLink> link_;
  bool injecting_ = false;
};

}  // namespace cell_detail

inline CellRun run_cell(const ProtocolCase& pc, FaultKind kind, std::uint64_t seed) {
  CellRun out;
  const rig::Rig rig = config::load_rig_text(pc.rig_text, std::string(pc.name) + ".yaml");
  const playback::Show show = cell_detail::fault_matrix_show();
  cell_detail::Figure figure(rig, pc, kind, seed, out);
  // Nothing is injected yet. A device on a pseudo-terminal answers from the host's thread, which
  // a loaded machine may keep from answering a ping within a 10 ms reply timeout: start (which
  // only pings, clears and configures) may be tried again, as an operator would.
  Status started = Status::timeout;
  for (int attempt = 0; attempt < 50 && started != Status::ok; ++attempt) started = figure.link().start();
  if (started != Status::ok) {
    out.problem = "start: " + std::string(to_string(started)) + " " + figure.link().start_problem();
    return out;
  }
  out.started = true;
  control::ControllerOptions options;
  options.tick_period_s = 1.0 / rig.rate_hz;
  options.stage_clock = nullptr;
  control::Controller controller(rig, show, {&figure.link()}, options);
  controller.begin(0.0, rig.rest_frame());
  control::RunOptions run{rig.rate_hz, control::ClockMode::stepped, {}};
  run.plant = &figure;
  const std::atomic<int> no_interrupts{0};
  (void)control::run_loop(controller, run, figure, no_interrupts);

  out.fault = controller.latched_fault();
  out.link_dead = controller.supervisor().link_dead(0);
  out.end_phase = controller.phase();
  out.show_time_reached = controller.show_time();
  out.show_end = controller.show_end();
  out.tick_s = options.tick_period_s;
  out.watchdog_s = rig.links[0].watchdog_s;
  if (const auto* can = std::get_if<rig::CanOptions>(&rig.links[0].options); can && can->heartbeat_timeout_ms)
    out.watchdog_s = std::max(out.watchdog_s, static_cast<double>(*can->heartbeat_timeout_ms) / 1000.0);
  out.final_command.assign(controller.commanded().begin(), controller.commanded().end());
  out.rest = rig.rest_frame();
  figure.finish(controller);
  return out;
}

}  // namespace avar::fault_matrix
