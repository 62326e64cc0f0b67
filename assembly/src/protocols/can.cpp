#include "avar/assembly/can_protocol.hpp"
#include "avar/assembly/simulated_can_bus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "avar/assembly/can_drive.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/can_link.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/slcan_transport.hpp"
#include "avar/firmware_iface/socketcan_transport.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"

namespace avar::assembly {
namespace {

bool is_device_path(const std::string& port) { return port.rfind("/dev/", 0) == 0; }

/// How a link reaches its bus: `interface` as written, else by the port's form.
bool uses_slcan(const rig::LinkSpec& link, const std::string& port) {
  switch (link.options_as<rig::CanOptions>().interface) {
    case rig::CanInterface::slcan: return true;
    case rig::CanInterface::socketcan: return false;
    case rig::CanInterface::by_port: break;
  }
  return is_device_path(port);
}

/// The drive sets of a link: one per drive protocol, actuators in rig order.
std::vector<std::unique_ptr<firmware_iface::CanDrives>> make_drive_sets(const rig::Rig& rig, std::size_t link,
                                                                        const CanBusOptions& bus) {
  std::vector<std::unique_ptr<firmware_iface::CanDrives>> sets;
  for (const CanDriveProtocol* drive : can_drive_protocols()) {
    std::vector<const rig::ActuatorSpec*> mine;
    for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link}))
      if (a.drive == drive->name) mine.push_back(&a);
    if (!mine.empty()) sets.push_back(drive->make_drives(rig, mine, bus));
  }
  return sets;
}

firmware_iface::CanLinkConfig link_config(const rig::Rig& rig, std::size_t link, const CanBusOptions& bus, const std::string& how,
                                          const DriverTuning& tuning) {
  firmware_iface::CanLinkConfig config;
  // A simulated adapter answers from a thread of this process, which a busy machine may keep
  // waiting: give it up to 100 ms. Unlike a servo bus, a late CAN reply only counts toward the
  // drive's silence budget, so this need not cover the worst stall.
  DriverTuning can_tuning = tuning;
  can_tuning.min_reply_timeout_ms = std::min(tuning.min_reply_timeout_ms, 100);
  config.reply_timeout = can_tuning.reply_timeout(std::chrono::milliseconds(bus.reply_timeout_ms));
  config.description = "CAN bus '" + rig.links[link].name + "' (" + how + ")";
  return config;
}

SimulatedDevice simulated_can(const rig::Rig& rig, std::size_t link) {
  auto device = std::make_unique<SimulatedCanBus>(rig, link);
  SimulatedCanBus* d = device.get();
  return {std::move(device),
          [d, &rig](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->device_position(index_on_link(rig, a))); }};
}

/// The drive protocol `--drive` names.
ServedDevice standalone_can(const SimValues& values) {
  const CanDriveProtocol* drive = find_can_drive(values.text("drive"));
  if (!drive)
    throw SimOptionError("--drive: '" + values.text("drive") +
                         "' is not a CAN drive protocol; expected one of: " + rig::drive_names());
  return standalone_slcan(*drive, values);
}

/// A simulated SLCAN adapter on a bus: the help of every offer that serves one.
constexpr const char* kSlcanHelp =
    "A simulated SLCAN (Lawicel) USB-CAN adapter, such as a CANable, with simulated drives on its bus: it opens at "
    "the bus bitrate (S-command), passes frames both ways and reports its status. Any SLCAN client can open it: "
    "avar (a rig link with port: /dev/pts/N), python-can's slcan interface, slcand. Inside avar, a can link with "
    "port: sim runs the same drives on this adapter; tests also use an in-memory bus.";

}  // namespace

CanBusOptions can_bus_options(const rig::Rig& rig, std::size_t link) {
  const rig::CanOptions& o = rig.links[link].options_as<rig::CanOptions>();
  CanBusOptions bus;
  bus.bitrate = o.bitrate;
  bus.reply_timeout_ms = o.reply_timeout_ms;
  bus.heartbeat_ms = o.heartbeat_ms;
  bus.mit_master_id = o.mit_master_id;
  bus.silent_ticks = firmware_iface::silence_budget(o.heartbeat_timeout_s(), rig.rate_hz);
  return bus;
}

ServedDevice standalone_slcan(const CanDriveProtocol& drive, const SimValues& values) {
  const rig::CanDriveSchema& schema = schema_of(drive);
  const long long bitrate = values.integer("bitrate");
  if (bitrate <= 0 || bitrate > 1'000'000 || !firmware_iface::is_standard_can_bitrate(static_cast<int>(bitrate)))
    throw SimOptionError(
        "--bitrate: " + values.text("bitrate") +
        " is not a CAN bitrate; expected 10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000 or 1000000");
  if (!schema.accepts_bitrate(static_cast<int>(bitrate)))
    throw SimOptionError("--bitrate: a " + std::string(schema.device_name) + " cannot run at " + values.text("bitrate") +
                         "; expected one of: " + schema.bitrates_text);
  CanBusOptions bus;
  bus.bitrate = static_cast<int>(bitrate);
  auto drives = std::make_shared<std::vector<SimulatedDrive>>();
  std::vector<sim::CanNode*> nodes;
  std::vector<long long> ids;
  std::string id_text;
  for (long long id : values.integers("ids")) {
    if (id < schema.node_low || id > schema.node_high)
      throw SimOptionError("--ids: " + std::to_string(id) + " is not a " + schema.device_name + " node; expected " +
                           std::to_string(schema.node_low) + " to " + std::to_string(schema.node_high));
    if (std::find(ids.begin(), ids.end(), id) != ids.end())
      throw SimOptionError("--ids: " + std::to_string(id) + " is given twice; every drive on a bus needs its own node id");
    ids.push_back(id);
    drives->push_back(drive.make_simulated(nullptr, static_cast<std::uint32_t>(id), 0, bus));
    nodes.push_back(drives->back().node.get());
    id_text += (id_text.empty() ? "" : ",") + std::to_string(id);
  }

  /// The adapter, owning the drives on its bus (declared first: the adapter borrows them).
  class AdapterWithDrives final : public sim::ByteDevice {
   public:
    AdapterWithDrives(std::shared_ptr<std::vector<SimulatedDrive>> drives, int bitrate, const std::vector<sim::CanNode*>& nodes)
        : drives_(std::move(drives)), adapter_(sim::SimSlcanConfig{.bus_bitrate = bitrate}, nodes) {}
    void receive(std::span<const std::uint8_t> bytes) override { adapter_.receive(bytes); }
    std::size_t take_replies(std::span<std::uint8_t> out) override { return adapter_.take_replies(out); }
    void advance(double dt_s) override { adapter_.advance(dt_s); }
    std::uint64_t bytes_received() const override { return adapter_.bytes_received(); }

   private:
    std::shared_ptr<std::vector<SimulatedDrive>> drives_;
    sim::SimSlcanAdapter adapter_;
  };

  ServedDevice out;
  out.device = std::make_unique<AdapterWithDrives>(drives, bus.bitrate, nodes);
  out.description = "simulated SLCAN adapter with " + std::string(schema.device_name) + (ids.size() == 1 ? "" : "s") +
                    " at node" + (ids.size() == 1 ? " " : "s ") + id_text + " on a " + std::to_string(bitrate) + " bit/s bus";
  out.state = [drives, unit = std::string(schema.device_unit)] {
    std::string line = "positions (" + unit + "):";
    char value[24];
    for (std::size_t i = 0; i < drives->size() && i < 8; ++i) {
      std::snprintf(value, sizeof value, " %.3f", (*drives)[i].device_position());
      line += value;
    }
    return line;
  };
  return out;
}

SimOffer drive_sim_offer(const char* name, const char* summary, const char* example) {
  return SimOffer{
      .name = name,
      .alias = nullptr,
      .summary = summary,
      .description = kSlcanHelp,
      .transport = SimTransport::pty,
      .example = example,
      .options = {{"ids", "1", "Node ids of the drives, comma-separated"},
                  {"bitrate", "1000000", "Bus bitrate in bit/s; open the adapter at the same rate"}},
      .make = nullptr,
  };
}

namespace {

std::unique_ptr<firmware_iface::ActuatorLink> slcan_link(const rig::Rig& rig, std::size_t link,
                                                         firmware_iface::ByteTransport& serial, const DriverTuning& tuning) {
  const CanBusOptions bus = can_bus_options(rig, link);
  auto transport = std::make_unique<firmware_iface::SlcanTransport>(serial, bus.bitrate);
  return std::make_unique<firmware_iface::CanLink>(std::move(transport), make_drive_sets(rig, link, bus),
                                                   link_config(rig, link, bus, "SLCAN on " + serial.name(), tuning));
}

/// Through an SLCAN adapter (a serial port, or a simulated adapter's), else on SocketCAN.
OpenedLink open_can(const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
  if (at.bytes || at.simulated || uses_slcan(rig.links[link], at.port)) return open_over_bytes(rig, link, at, slcan_link);
  const CanBusOptions bus = can_bus_options(rig, link);
  auto transport = std::make_unique<firmware_iface::SocketCanTransport>(at.port, bus.bitrate);
  OpenedLink opened;
  opened.driver = std::make_unique<firmware_iface::CanLink>(std::move(transport), make_drive_sets(rig, link, bus),
                                                            link_config(rig, link, bus, "SocketCAN " + at.port, at.tuning));
  return opened;
}

}  // namespace

const Protocol& can_protocol() {
  static const Protocol p{
      .name = "can",
      .open = open_can,
      .make_simulated = simulated_can,
      .simulation_runs_during_start = true,
      .sim =
          {
              .name = "can",
              .alias = "slcan",
              .summary = "A simulated SLCAN USB-CAN adapter with simulated drives (odrive, cia402, mit) on its bus",
              .description = kSlcanHelp,
              .transport = SimTransport::pty,
              .example = "  avar sim can --drive odrive --ids 1,2,3   # prints /dev/pts/N (also: avar sim slcan)\n"
                         "  avar play examples/shows/odrive-arm.yaml --rig examples/rigs/odrive-arm.yaml --port /dev/pts/N",
              .options = {{"drive", "odrive", "The drives on the bus: odrive (CAN Simple), cia402 (CANopen) or mit"},
                          {"ids", "1", "Node ids of the drives, comma-separated"},
                          {"bitrate", "1000000", "Bus bitrate in bit/s; open the adapter at the same rate"}},
              .make = standalone_can,
          },
  };
  return p;
}

}  // namespace avar::assembly
