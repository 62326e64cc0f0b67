#include <cmath>
#include <stdexcept>

#include "../setting_reading.hpp"
#include "avar/assembly/dmx_protocol.hpp"
#include "avar/assembly/network_dmx_protocol.hpp"
#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/sim/sim_dmx_node.hpp"

namespace avar::assembly {
namespace {

constexpr std::string_view kArtnetKeys[] = {"to", "broadcast", "net", "subnet", "universe", "slots"};
constexpr std::string_view kSacnKeys[] = {
    "to", "universe", "priority", "source_name", "cid", "preview", "multicast_ttl", "multicast_interface", "discovery", "slots"};

/// The destination written as `to` (or the override), as the sender takes it.
firmware_iface::UdpDestination network_destination(const rig::LinkSpec& link, const std::string& override_text,
                                                   std::uint16_t default_port) {
  const ScalarValue* to = link.settings.find("to");
  const std::string text = !override_text.empty() ? override_text : to ? to->text : "";
  if (text.empty()) return {"", default_port, false, 1, true, ""};
  try {
    return firmware_iface::parse_udp_destination(text, default_port);
  } catch (const std::invalid_argument& e) {
    if (to && override_text.empty()) to->fail(e.what());
    throw InputError(link.where, "link '" + link.name + "': " + e.what());
  }
}

std::size_t slots_setting(const rig::LinkSpec& link) {
  const ScalarValue* s = link.settings.find("slots");
  return s ? static_cast<std::size_t>(integer_in(*s, "slots", 1, 512)) : 0;
}

bool bool_setting(const rig::LinkSpec& link, const char* key, bool otherwise) {
  const ScalarValue* v = link.settings.find(key);
  return v ? v->as_bool(key) : otherwise;
}

long long integer_setting(const rig::LinkSpec& link, const char* key, long long low, long long high, long long otherwise) {
  const ScalarValue* v = link.settings.find(key);
  return v ? integer_in(*v, key, low, high) : otherwise;
}

std::uint16_t artnet_port_address(const rig::LinkSpec& link) {
  return firmware_iface::artnet::port_address(static_cast<unsigned>(integer_setting(link, "net", 0, 127, 0)),
                                              static_cast<unsigned>(integer_setting(link, "subnet", 0, 15, 0)),
                                              static_cast<unsigned>(integer_setting(link, "universe", 0, 15, 0)));
}

void validate_artnet(const rig::LinkSpec& link) {
  link.settings.expect_only_keys(kArtnetKeys);
  (void)artnet_port_address(link);
  (void)slots_setting(link);
  const bool broadcast = bool_setting(link, "broadcast", false);
  const ScalarValue* to = link.settings.find("to");
  if (!to && !link.simulated())
    ScalarValue{"", false, "no destination", link.settings.where}.fail(
        "expected `to: NODE_IP` in " + link.settings.what +
        ": Art-Net goes to a stated node (broadcast only with `to: 2.255.255.255, broadcast: true`)");
  const firmware_iface::UdpDestination d = network_destination(link, "", firmware_iface::artnet::kUdpPort);
  if (to && !broadcast && (d.host == "255.255.255.255" || d.host.ends_with(".255")))
    to->fail("expected a node's address; " + to->describe() +
             " looks like a broadcast address: add broadcast: true to send to every node");
}

void validate_sacn(const rig::LinkSpec& link) {
  link.settings.expect_only_keys(kSacnKeys);
  const ScalarValue* universe = link.settings.find("universe");
  if (!universe)
    ScalarValue{"", false, "no universe", link.settings.where}.fail("expected `universe: 1..63999` in " + link.settings.what);
  (void)integer_in(*universe, "universe", firmware_iface::sacn::kMinUniverse, firmware_iface::sacn::kMaxUniverse);
  (void)integer_setting(link, "priority", 0, firmware_iface::sacn::kMaxPriority, firmware_iface::sacn::kDefaultPriority);
  (void)integer_setting(link, "multicast_ttl", 1, 255, 1);
  (void)slots_setting(link);
  (void)bool_setting(link, "preview", false);
  (void)bool_setting(link, "discovery", true);
  if (const ScalarValue* name = link.settings.find("source_name")) {
    if (name->as_string("source_name").size() > 63)
      name->fail("expected a source_name of at most 63 bytes, found " + name->describe());
  }
  if (const ScalarValue* cid = link.settings.find("cid")) {
    firmware_iface::sacn::Cid parsed{};
    if (!parse_cid(cid->as_string("cid"), parsed))
      cid->fail("expected cid to be a UUID such as 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f, found " + cid->describe());
  }
  if (const ScalarValue* interface = link.settings.find("multicast_interface")) {
    try {
      (void)firmware_iface::parse_udp_destination(interface->as_string("multicast_interface"), 1);
    } catch (const std::invalid_argument&) {
      interface->fail("expected multicast_interface to be the IPv4 address of an interface, found " + interface->describe());
    }
  }
  (void)network_destination(link, "", firmware_iface::sacn::kUdpPort);
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

/// The address rule every DMX carrier shares.
AddressRule dmx_slot_rule(const rig::LinkSpec&, bool fine) {
  return {"address", 1, fine ? 511 : 512, "min_level", "max_level", "trim", 0, fine ? 65535.0 : 255.0, "DMX level"};
}

std::unique_ptr<firmware_iface::ActuatorLink> no_serial_link(const rig::Rig& rig, std::size_t link,
                                                             firmware_iface::ByteTransport&, const DriverTuning&) {
  throw std::logic_error("link '" + rig.links[link].name + "' is on the network, not a serial port");
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

/// A DMX-on-the-network protocol: no port, no baud, DMX slot addresses, its own link opener.
Protocol network_protocol(const char* name, const char* device_name, const char* bauds_text,
                          void (*validate)(const rig::LinkSpec&), SimulatedDevice (*make_simulated)(const rig::Rig&, std::size_t),
                          std::unique_ptr<firmware_iface::ActuatorLink> (*open)(const rig::Rig&, std::size_t,
                                                                                const std::string&)) {
  Protocol g{name,           device_name,   0,    bauds_text, [](int) { return true; },
             validate,       dmx_slot_rule, true, false,      [](const rig::LinkSpec&) { return false; },
             no_serial_link, make_simulated};
  g.port_optional = [](const rig::LinkSpec&) { return true; };
  g.port_is_serial = [](const rig::LinkSpec&, const std::string&) { return false; };
  g.open_link = open;
  return g;
}

}  // namespace

bool parse_cid(const std::string& text, firmware_iface::sacn::Cid& cid) {
  if (text.size() != 36) return false;
  std::size_t byte = 0;
  for (std::size_t i = 0; i < text.size();) {
    if (i == 8 || i == 13 || i == 18 || i == 23) {
      if (text[i] != '-') return false;
      ++i;
      continue;
    }
    const auto hex = [](char c) -> int {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      if (c >= 'A' && c <= 'F') return c - 'A' + 10;
      return -1;
    };
    const int hi = hex(text[i]), lo = hex(text[i + 1]);
    if (hi < 0 || lo < 0) return false;
    cid[byte++] = static_cast<std::uint8_t>(hi << 4 | lo);
    i += 2;
  }
  return byte == cid.size();
}

firmware_iface::ArtnetLinkConfig artnet_config(const rig::Rig& rig, std::size_t link, const std::string& destination) {
  const rig::LinkSpec& spec = rig.links[link];
  firmware_iface::ArtnetLinkConfig config;
  config.destination = network_destination(spec, destination, firmware_iface::artnet::kUdpPort);
  config.destination.broadcast = bool_setting(spec, "broadcast", false);
  config.port_address = artnet_port_address(spec);
  config.slot_count = slots_setting(spec);
  config.actuators = dmx_actuators(rig, link);
  return config;
}

firmware_iface::SacnLinkConfig sacn_config(const rig::Rig& rig, std::size_t link, const std::string& destination) {
  const rig::LinkSpec& spec = rig.links[link];
  firmware_iface::SacnLinkConfig config;
  config.destination = network_destination(spec, destination, firmware_iface::sacn::kUdpPort);
  config.destination.multicast_ttl = static_cast<int>(integer_setting(spec, "multicast_ttl", 1, 255, 1));
  if (const ScalarValue* interface = spec.settings.find("multicast_interface"))
    config.destination.multicast_interface = interface->text;
  config.universe = static_cast<std::uint16_t>(integer_setting(spec, "universe", 1, 63999, 1));
  config.priority = static_cast<std::uint8_t>(integer_setting(spec, "priority", 0, 200, 100));
  config.source_name =
      spec.settings.find("source_name") ? spec.settings.find("source_name")->text : "avar " + rig.name + " " + spec.name;
  if (config.source_name.size() > 63) config.source_name.resize(63);
  if (const ScalarValue* cid = spec.settings.find("cid")) (void)parse_cid(cid->text, config.cid);
  else config.cid = derived_cid(rig.name, spec.name);
  config.preview = bool_setting(spec, "preview", false);
  config.slot_count = slots_setting(spec);
  if (bool_setting(spec, "discovery", true))
    config.discovery_every =
        static_cast<std::uint32_t>(std::max(1L, std::lround(rig.rate_hz * firmware_iface::sacn::kDiscoveryIntervalS)));
  config.actuators = dmx_actuators(rig, link);
  return config;
}

const Protocol& artnet_protocol() {
  static const Protocol p = network_protocol(
      "artnet", "Art-Net node", "none (Art-Net is on the network)", validate_artnet,
      [](const rig::Rig& rig, std::size_t link) {
        return simulated_node(sim::DmxNodeProtocol::artnet, artnet_port_address(rig.links[link]));
      },
      [](const rig::Rig& rig, std::size_t link, const std::string& port) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        return std::make_unique<firmware_iface::ArtnetLink>(artnet_config(rig, link, port));
      });
  return p;
}

const Protocol& sacn_protocol() {
  static const Protocol p = network_protocol(
      "sacn", "sACN receiver", "none (sACN is on the network)", validate_sacn,
      [](const rig::Rig& rig, std::size_t link) {
        const auto universe = static_cast<std::uint16_t>(integer_setting(rig.links[link], "universe", 1, 63999, 1));
        return simulated_node(sim::DmxNodeProtocol::sacn, universe);
      },
      [](const rig::Rig& rig, std::size_t link, const std::string& port) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        return std::make_unique<firmware_iface::SacnLink>(sacn_config(rig, link, port));
      });
  return p;
}

}  // namespace avar::assembly
