// DMX512 on the network, one universe per link: `artnet: {to, broadcast, net, subnet, universe,
// slots}` and `sacn: {to, universe, priority, source_name, cid, preview, multicast_ttl,
// multicast_interface, discovery, slots}`. The link needs no port.
#include <stdexcept>

#include "avar/firmware_iface/artnet_header.hpp"
#include "avar/firmware_iface/sacn_codec.hpp"
#include "avar/firmware_iface/udp_destination.hpp"
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

constexpr std::string_view kArtnetKeys[] = {"to", "broadcast", "net", "subnet", "universe", "slots"};
constexpr std::string_view kSacnKeys[] = {
    "to", "universe", "priority", "source_name", "cid", "preview", "multicast_ttl", "multicast_interface", "discovery", "slots"};

/// "01234567-89ab-cdef-0123-456789abcdef" -> CID; false when the text is no UUID.
bool parse_cid(const std::string& text, std::array<std::uint8_t, 16>& cid) {
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

/// `to` as written, checked as a destination; its host for the broadcast check.
NetworkTarget network_target(const LinkSettings& s, std::uint16_t default_port, std::string* host) {
  NetworkTarget target{"", s.where};
  const ScalarValue* to = s.find("to");
  if (!to) return target;
  target.text = to->text;
  target.where = to->where;
  try {
    const firmware_iface::UdpDestination d = firmware_iface::parse_udp_destination(to->text, default_port);
    if (host) *host = d.host;
  } catch (const std::invalid_argument& e) {
    to->fail(e.what());
  }
  return target;
}

std::size_t slots_setting(const LinkSettings& s) {
  const ScalarValue* v = s.find("slots");
  return v ? static_cast<std::size_t>(integer_in(*v, "slots", 1, 512)) : 0;
}

bool bool_setting(const LinkSettings& s, const char* key, bool otherwise) {
  const ScalarValue* v = s.find(key);
  return v ? v->as_bool(key) : otherwise;
}

long long integer_setting(const LinkSettings& s, const char* key, long long low, long long high, long long otherwise) {
  const ScalarValue* v = s.find(key);
  return v ? integer_in(*v, key, low, high) : otherwise;
}

LinkOptions parse_artnet(const LinkSpec& link, const LinkSettings& s) {
  s.expect_only_keys(kArtnetKeys);
  ArtnetOptions o;
  o.net = static_cast<unsigned>(integer_setting(s, "net", 0, 127, 0));
  o.subnet = static_cast<unsigned>(integer_setting(s, "subnet", 0, 15, 0));
  o.universe = static_cast<unsigned>(integer_setting(s, "universe", 0, 15, 0));
  o.slots = slots_setting(s);
  o.broadcast = bool_setting(s, "broadcast", false);
  const ScalarValue* to = s.find("to");
  if (!to && !link.simulated())
    ScalarValue{"", false, "no destination", s.where}.fail(
        "expected `to: NODE_IP` in " + s.what +
        ": Art-Net goes to a stated node (broadcast only with `to: 2.255.255.255, broadcast: true`)");
  std::string host;
  o.to = network_target(s, firmware_iface::artnet::kUdpPort, &host);
  if (to && !o.broadcast && (host == "255.255.255.255" || host.ends_with(".255")))
    to->fail("expected a node's address; " + to->describe() +
             " looks like a broadcast address: add broadcast: true to send to every node");
  return o;
}

LinkOptions parse_sacn(const LinkSpec&, const LinkSettings& s) {
  namespace sacn = firmware_iface::sacn;
  s.expect_only_keys(kSacnKeys);
  SacnOptions o;
  const ScalarValue* universe = s.find("universe");
  if (!universe) ScalarValue{"", false, "no universe", s.where}.fail("expected `universe: 1..63999` in " + s.what);
  o.universe = static_cast<std::uint16_t>(integer_in(*universe, "universe", sacn::kMinUniverse, sacn::kMaxUniverse));
  o.priority = static_cast<std::uint8_t>(integer_setting(s, "priority", 0, sacn::kMaxPriority, sacn::kDefaultPriority));
  o.multicast_ttl = static_cast<int>(integer_setting(s, "multicast_ttl", 1, 255, 1));
  o.slots = slots_setting(s);
  o.preview = bool_setting(s, "preview", false);
  o.discovery = bool_setting(s, "discovery", true);
  if (const ScalarValue* name = s.find("source_name")) {
    if (name->as_string("source_name").size() > 63)
      name->fail("expected a source_name of at most 63 bytes, found " + name->describe());
    o.source_name = name->text;
  }
  if (const ScalarValue* cid = s.find("cid")) {
    std::array<std::uint8_t, 16> parsed{};
    if (!parse_cid(cid->as_string("cid"), parsed))
      cid->fail("expected cid to be a UUID such as 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f, found " + cid->describe());
    o.cid = parsed;
  }
  if (const ScalarValue* interface = s.find("multicast_interface")) {
    try {
      (void)firmware_iface::parse_udp_destination(interface->as_string("multicast_interface"), 1);
    } catch (const std::invalid_argument&) {
      interface->fail("expected multicast_interface to be the IPv4 address of an interface, found " + interface->describe());
    }
    o.multicast_interface = interface->text;
  }
  o.to = network_target(s, sacn::kUdpPort, nullptr);
  return o;
}

}  // namespace

const ProtocolSchema& artnet_schema() {
  static const ProtocolSchema p{
      .name = "artnet",
      .device_name = "Art-Net node",
      .default_baud = 0,
      .bauds_text = "none (Art-Net is on the network)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_artnet,
      .port_optional = [](const LinkSettings&) { return true; },
      .address_rule = dmx_slot_rule,
      .has_fine_addresses = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

const ProtocolSchema& sacn_schema() {
  static const ProtocolSchema p{
      .name = "sacn",
      .device_name = "sACN receiver",
      .default_baud = 0,
      .bauds_text = "none (sACN is on the network)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_sacn,
      .port_optional = [](const LinkSettings&) { return true; },
      .address_rule = dmx_slot_rule,
      .has_fine_addresses = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

}  // namespace avar::rig
