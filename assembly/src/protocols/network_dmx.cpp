#include <cmath>
#include <stdexcept>

#include "avar/assembly/dmx_protocol.hpp"
#include "avar/assembly/network_dmx_protocol.hpp"
#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/sim/sim_dmx_node.hpp"

namespace avar::assembly {
namespace {

/// The destination written as `to` (or the override "HOST[:PORT]"), as the sender takes it.
firmware_iface::UdpDestination network_destination(const rig::LinkSpec& link, const rig::NetworkTarget& to,
                                                   const std::string& override_text, std::uint16_t default_port) {
  const std::string& text = !override_text.empty() ? override_text : to.text;
  if (text.empty()) return {"", default_port, false, 1, true, ""};
  try {
    return firmware_iface::parse_udp_destination(text, default_port);
  } catch (const std::invalid_argument& e) {
    // `to` was checked at load: only a destination from the command line gets here.
    throw InputError(link.where, "link '" + link.name + "': " + e.what());
  }
}

std::uint16_t artnet_port_address(const rig::ArtnetOptions& o) {
  return firmware_iface::artnet::port_address(o.net, o.subnet, o.universe);
}

/// A CID that stays the same from run to run for the same rig and link (receivers track sources
/// by CID): FNV-1a of the names, shaped as a name-based UUID.
firmware_iface::sacn::Cid derived_cid(const std::string& rig_name, const std::string& link_name) {
  firmware_iface::sacn::Cid cid{};
  const std::string text = "avar/" + rig_name + "/" + link_name;
  for (std::size_t half = 0; half < 2; ++half) {
    std::uint64_t h = 0xcbf29ce484222325ULL ^ half;
    for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
    for (std::size_t i = 0; i < 8; ++i) cid[half * 8 + i] = static_cast<std::uint8_t>(h >> (8 * i));
  }
  cid[6] = static_cast<std::uint8_t>((cid[6] & 0x0FU) | 0x50U);
  cid[8] = static_cast<std::uint8_t>((cid[8] & 0x3FU) | 0x80U);
  return cid;
}

/// A node on loopback listening to the link's universe; the truth is the level it outputs.
SimulatedDevice simulated_node(sim::DmxNodeProtocol protocol, std::uint16_t universe) {
  sim::SimDmxNodeConfig config;
  config.protocol = protocol;
  config.universe = universe;
  auto node = std::make_unique<sim::SimDmxNode>(config);
  sim::SimDmxNode* n = node.get();
  SimulatedDevice d{nullptr,
                    [n](const rig::ActuatorSpec& a) { return a.calibration.to_channel(n->level(a.device_channel, a.fine)); }};
  d.network_node = std::move(node);
  return d;
}

/// `avar sim artnet|sacn`: a node on loopback listening to one universe.
ServedDevice standalone_node(sim::DmxNodeProtocol protocol, std::uint16_t universe, const SimValues& values) {
  const long long port = values.integer("udp-port");
  if (port < 0 || port > 65535) throw SimOptionError("--udp-port: " + values.text("udp-port") + " is outside 0 to 65535");
  sim::SimDmxNodeConfig config;
  config.protocol = protocol;
  config.universe = universe;
  config.port = static_cast<std::uint16_t>(port);
  ServedDevice out;
  try {
    out.network_node = std::make_unique<sim::SimDmxNode>(config);
  } catch (const std::runtime_error& e) {
    throw SimOptionError("--udp-port: " + std::string(e.what()));
  }
  const sim::SimDmxNode* n = out.network_node.get();
  out.description = std::string(protocol == sim::DmxNodeProtocol::artnet ? "simulated Art-Net node (Port-Address "
                                                                         : "simulated sACN receiver (universe ") +
                    std::to_string(universe) + ")";
  out.state = [n] {
    std::string line = std::to_string(n->counters().packets) + " packets; slots:";
    for (int address = 1; address <= 16; ++address) line += " " + std::to_string(n->slot(address));
    return line;
  };
  return out;
}

ServedDevice standalone_artnet(const SimValues& values) {
  const auto in = [&](const char* name, long long high) {
    const long long v = values.integer(name);
    if (v < 0 || v > high)
      throw SimOptionError("--" + std::string(name) + ": " + values.text(name) + " is outside 0 to " + std::to_string(high));
    return static_cast<unsigned>(v);
  };
  const std::uint16_t address = firmware_iface::artnet::port_address(in("net", 127), in("subnet", 15), in("universe", 15));
  return standalone_node(sim::DmxNodeProtocol::artnet, address, values);
}

ServedDevice standalone_sacn(const SimValues& values) {
  const long long universe = values.integer("universe");
  if (universe < firmware_iface::sacn::kMinUniverse || universe > firmware_iface::sacn::kMaxUniverse)
    throw SimOptionError("--universe: " + values.text("universe") + " is outside 1 to 63999");
  return standalone_node(sim::DmxNodeProtocol::sacn, static_cast<std::uint16_t>(universe), values);
}

/// A DMX-on-the-network protocol: no port; `open` sends to the endpoint's port when given (a
/// simulated node's, or --port HOST[:PORT]), else to the rig's destination.
Protocol network_protocol(const char* name, SimulatedDevice (*make_simulated)(const rig::Rig&, std::size_t),
                          OpenedLink (*open)(const rig::Rig&, std::size_t, LinkEndpoint), SimOffer sim) {
  return Protocol{
      .name = name,
      .open = open,
      .make_simulated = make_simulated,
      .sim = std::move(sim),
  };
}

}  // namespace

firmware_iface::ArtnetLinkConfig artnet_config(const rig::Rig& rig, std::size_t link, const std::string& destination) {
  const rig::LinkSpec& spec = rig.links[link];
  const rig::ArtnetOptions& o = spec.options_as<rig::ArtnetOptions>();
  firmware_iface::ArtnetLinkConfig config;
  config.destination = network_destination(spec, o.to, destination, firmware_iface::artnet::kUdpPort);
  config.destination.broadcast = o.broadcast;
  config.port_address = artnet_port_address(o);
  config.slot_count = o.slots;
  config.actuators = dmx_actuators(rig, link);
  return config;
}

firmware_iface::SacnLinkConfig sacn_config(const rig::Rig& rig, std::size_t link, const std::string& destination) {
  const rig::LinkSpec& spec = rig.links[link];
  const rig::SacnOptions& o = spec.options_as<rig::SacnOptions>();
  firmware_iface::SacnLinkConfig config;
  config.destination = network_destination(spec, o.to, destination, firmware_iface::sacn::kUdpPort);
  config.destination.multicast_ttl = o.multicast_ttl;
  config.destination.multicast_interface = o.multicast_interface;
  config.universe = o.universe;
  config.priority = o.priority;
  config.source_name = o.source_name ? *o.source_name : "avar " + rig.name + " " + spec.name;
  if (config.source_name.size() > 63) config.source_name.resize(63);
  config.cid = o.cid ? *o.cid : derived_cid(rig.name, spec.name);
  config.preview = o.preview;
  config.slot_count = o.slots;
  if (o.discovery)
    config.discovery_every =
        static_cast<std::uint32_t>(std::max(1L, std::lround(rig.rate_hz * firmware_iface::sacn::kDiscoveryIntervalS)));
  config.actuators = dmx_actuators(rig, link);
  return config;
}

const Protocol& artnet_protocol() {
  static const Protocol p = network_protocol(
      "artnet",
      [](const rig::Rig& rig, std::size_t link) {
        return simulated_node(sim::DmxNodeProtocol::artnet,
                              artnet_port_address(rig.links[link].options_as<rig::ArtnetOptions>()));
      },
      [](const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
        return OpenedLink{std::make_unique<firmware_iface::ArtnetLink>(artnet_config(rig, link, at.port)), nullptr};
      },
      SimOffer{
          .name = "artnet",
          .alias = nullptr,
          .summary = "A simulated Art-Net node on loopback UDP (one DMX universe)",
          .description = "An Art-Net 4 node that outputs one Port-Address (net:subnet:universe): it takes ArtDmx "
                         "packets in sequence, answers ArtPoll, and holds the universe's 512 slots. It listens on "
                         "127.0.0.1, on --udp-port or any free port.",
          .transport = SimTransport::udp_loopback,
          .example =
              "  avar sim artnet --universe 1 --udp-port 6454      # prints 127.0.0.1:6454\n"
              "  avar play SHOW.yaml --rig RIG.yaml --port 127.0.0.1:6454  # a one-link rig: artnet: {to: ..., universe: 1}",
          .options = {{"net", "0", "Art-Net net, 0 to 127"},
                      {"subnet", "0", "Art-Net subnet, 0 to 15"},
                      {"universe", "0", "Art-Net universe, 0 to 15"},
                      {"udp-port", "0", "UDP port on 127.0.0.1 (0: any free one)"}},
          .make = standalone_artnet,
      });
  return p;
}

const Protocol& sacn_protocol() {
  static const Protocol p = network_protocol(
      "sacn",
      [](const rig::Rig& rig, std::size_t link) {
        return simulated_node(sim::DmxNodeProtocol::sacn, rig.links[link].options_as<rig::SacnOptions>().universe);
      },
      [](const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
        return OpenedLink{std::make_unique<firmware_iface::SacnLink>(sacn_config(rig, link, at.port)), nullptr};
      },
      SimOffer{
          .name = "sacn",
          .alias = nullptr,
          .summary = "A simulated sACN (E1.31) receiver on loopback UDP (one DMX universe)",
          .description = "An E1.31 (streaming ACN) receiver of one universe: it takes data packets in sequence, "
                         "honours priority and stream termination, counts universe discovery, and holds the "
                         "universe's 512 slots. It listens on 127.0.0.1 (unicast), on --udp-port or any free port.",
          .transport = SimTransport::udp_loopback,
          .example = "  avar sim sacn --universe 1 --udp-port 5568         # prints 127.0.0.1:5568\n"
                     "  avar play SHOW.yaml --rig RIG.yaml --port 127.0.0.1:5568   # a one-link rig: sacn: {universe: 1}",
          .options = {{"universe", "1", "sACN universe, 1 to 63999"},
                      {"udp-port", "0", "UDP port on 127.0.0.1 (0: any free one)"}},
          .make = standalone_sacn,
      });
  return p;
}

}  // namespace avar::assembly
