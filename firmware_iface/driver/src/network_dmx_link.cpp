#include "avar/firmware_iface/network_dmx_link.hpp"

#include <arpa/inet.h>

#include <stdexcept>

#include "avar/firmware_iface/artnet_dmx_codec.hpp"

namespace avar::firmware_iface {
namespace {

/// sACN's destination: the universe's multicast group when no host is given.
UdpDestination sacn_destination(const SacnLinkConfig& c) {
  if (c.universe < sacn::kMinUniverse || c.universe > sacn::kMaxUniverse)
    throw std::invalid_argument("sACN universe " + std::to_string(c.universe) + " is outside 1..63999");
  UdpDestination d = c.destination;
  if (d.host.empty()) {
    in_addr group{};
    group.s_addr = htonl(sacn::multicast_group(c.universe));
    char text[INET_ADDRSTRLEN];
    ::inet_ntop(AF_INET, &group, text, sizeof text);
    d.host = text;
  }
  return d;
}

}  // namespace

NetworkDmxLink::NetworkDmxLink(std::vector<DmxActuator> actuators, std::size_t slot_count, std::size_t min_slots,
                               const UdpDestination& destination, std::size_t packet_capacity)
    : sender_(destination), universe_(std::move(actuators), slot_count, min_slots), packet_(packet_capacity) {}

Status NetworkDmxLink::send(std::span<const double> frame) noexcept {
  universe_.fill(frame);
  return transmit();
}

Status NetworkDmxLink::release() noexcept {
  universe_.zero_all();
  return transmit();
}

Status NetworkDmxLink::transmit() noexcept {
  const std::size_t n = encode(packet_, slots());
  if (n == 0) return Status::out_of_range;
  if (const Status s = sender_.send(std::span(packet_.data(), n)); s != Status::ok) return s;
  return after_packet();
}

LinkCounters NetworkDmxLink::counters() const noexcept {
  LinkCounters c;
  c.exchanges = sender_.datagrams_sent();
  c.bytes_sent = sender_.bytes_sent();
  c.timeouts = sender_.dropped();
  return c;
}

ArtnetLink::ArtnetLink(const ArtnetLinkConfig& config)
    : NetworkDmxLink(config.actuators, config.slot_count, 2, config.destination, artnet::kMaxDmxPacketSize),
      port_address_(config.port_address) {
  if (port_address_ > artnet::kMaxPortAddress)
    throw std::invalid_argument("Art-Net Port-Address " + std::to_string(port_address_) + " is above 32767");
  description_ = "Art-Net universe " + std::to_string(port_address_) + " (" + std::to_string(slot_count()) + " slots) to " +
                 sender_.describe();
}

std::size_t ArtnetLink::encode(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots) noexcept {
  sequence_ = static_cast<std::uint8_t>(sequence_ == 255 ? 1 : sequence_ + 1);
  return artnet::encode_dmx(out, sequence_, 0, port_address_, slots);
}

SacnLink::SacnLink(SacnLinkConfig config)
    : NetworkDmxLink(config.actuators, config.slot_count, 1, sacn_destination(config), sacn::kMaxDataPacketSize),
      config_(std::move(config)) {
  if (config_.priority > sacn::kMaxPriority)
    throw std::invalid_argument("sACN priority " + std::to_string(config_.priority) + " is above 200");
  header_.universe = config_.universe;
  header_.priority = config_.priority;
  header_.options = config_.preview ? sacn::kPreviewData : 0;
  if (config_.discovery_every > 0) {
    discovery_packet_.resize(sacn::kMaxDiscoveryPacketSize);
    const std::uint16_t universe = config_.universe;
    discovery_packet_.resize(
        sacn::encode_discovery(discovery_packet_, {config_.cid, config_.source_name}, 0, 0, std::span(&universe, 1)));
    since_discovery_ = config_.discovery_every - 1;  // the first one goes with the first packet
    if (sender_.multicast()) {
      UdpDestination d = sacn_destination(config_);
      in_addr group{};
      group.s_addr = htonl(sacn::multicast_group(sacn::kDiscoveryUniverse));
      char text[INET_ADDRSTRLEN];
      ::inet_ntop(AF_INET, &group, text, sizeof text);
      d.host = text;
      discovery_sender_ = std::make_unique<UdpSender>(d);
    }
  }
  description_ = "sACN universe " + std::to_string(config_.universe) + " priority " + std::to_string(config_.priority) + " (" +
                 std::to_string(slot_count()) + " slots) to " + sender_.describe();
}

SacnLink::~SacnLink() {
  // E1.31 6.2.6: a source that stops sends three packets with Stream_Terminated set, so that
  // receivers let go of it at once instead of after the 2.5 s data loss timeout.
  header_.options = static_cast<std::uint8_t>(header_.options | sacn::kStreamTerminated);
  std::vector<std::uint8_t> packet(sacn::kMaxDataPacketSize);
  for (int i = 0; i < 3; ++i) {
    const std::size_t n = encode(packet, slots());
    if (n > 0) (void)sender_.send(std::span(packet.data(), n));
  }
}

std::size_t SacnLink::encode(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots) noexcept {
  const std::size_t n = sacn::encode_data(out, {config_.cid, config_.source_name}, header_, slots);
  header_.sequence = static_cast<std::uint8_t>(header_.sequence + 1);
  return n;
}

Status SacnLink::after_packet() noexcept {
  if (config_.discovery_every == 0 || ++since_discovery_ < config_.discovery_every) return Status::ok;
  since_discovery_ = 0;
  ++discovery_sent_;
  return (discovery_sender_ ? *discovery_sender_ : sender_).send(discovery_packet_);
}

}  // namespace avar::firmware_iface
