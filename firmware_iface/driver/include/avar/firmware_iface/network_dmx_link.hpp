#pragma once
// DMX512 over the network: one universe of 8- and 16-bit actuators (DmxUniverse) sent as one
// UDP datagram every tick, as Art-Net 4 ArtDmx (ArtnetLink) or E1.31 sACN (SacnLink). Fire and
// forget: nothing is read back, start() checks nothing. Sequence numbers count every packet.
//
// Threads: send() and release() on one sending thread; release_channel(), counters() and
// saturated_pulses() from any thread. send() and release() are real-time safe: the universe is
// filled, encoded into a buffer sized at construction, and sent with one non-blocking sendto.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/dmx_universe.hpp"
#include "avar/firmware_iface/sacn_codec.hpp"
#include "avar/firmware_iface/udp_sender.hpp"

namespace avar::firmware_iface {

class NetworkDmxLink : public ActuatorLink {
 public:
  Status start() override { return Status::ok; }
  Status read_positions(std::span<double>, std::span<bool>) override { return Status::ok; }
  Status send(std::span<const double> frame) noexcept override;
  /// Every actuator's slots at level 0 (DMX has no "off").
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override { universe_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return universe_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  /// exchanges and bytes_sent: datagrams sent; timeouts: datagrams dropped for a full queue.
  LinkCounters counters() const noexcept override;

  std::size_t slot_count() const noexcept { return universe_.slots().size(); }
  /// The universe as last sent (slot 1 first). On the sending thread.
  std::span<const std::uint8_t> slots() const noexcept { return universe_.slots(); }

 protected:
  NetworkDmxLink(std::vector<DmxActuator> actuators, std::size_t slot_count, std::size_t min_slots,
                 const UdpDestination& destination, std::size_t packet_capacity);
  /// The packet for this tick's slots into `out`; 0 when it cannot be encoded. Real-time safe.
  virtual std::size_t encode(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots) noexcept = 0;
  /// After each packet (sACN: universe discovery now and then). Real-time safe.
  virtual Status after_packet() noexcept { return Status::ok; }

  std::string description_;
  UdpSender sender_;

 private:
  Status transmit() noexcept;

  DmxUniverse universe_;
  std::vector<std::uint8_t> packet_;
};

struct ArtnetLinkConfig {
  /// The node's address (Art-Net port 6454 unless stated); broadcast only when set there.
  UdpDestination destination{"127.0.0.1", 6454, false, 1, true, ""};
  std::uint16_t port_address = 0;  ///< 15 bits: Net << 8 | Sub-Net << 4 | Universe
  std::size_t slot_count = 0;      ///< 0 = up to the highest slot used (at least 2, even)
  std::vector<DmxActuator> actuators;
};

/// Art-Net 4 ArtDmx every tick, sequence 1..255 (0 is "no sequencing" and is skipped).
class ArtnetLink final : public NetworkDmxLink {
 public:
  /// Throws std::invalid_argument as DmxUniverse does, or for a Port-Address above 32767; as
  /// UdpSender for the destination.
  explicit ArtnetLink(const ArtnetLinkConfig& config);
  std::uint8_t last_sequence() const noexcept { return sequence_; }

 private:
  std::size_t encode(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots) noexcept override;
  std::uint16_t port_address_;
  std::uint8_t sequence_ = 0;
};

struct SacnLinkConfig {
  /// Where packets go: empty host = the universe's multicast group 239.255.hi.lo, port 5568.
  UdpDestination destination{"", sacn::kUdpPort, false, 1, true, ""};
  std::uint16_t universe = 1;                      ///< 1..63999
  std::uint8_t priority = sacn::kDefaultPriority;  ///< 0..200
  sacn::Cid cid{};
  std::string source_name = "avar";
  bool preview = false;        ///< marks the data as not for live output
  std::size_t slot_count = 0;  ///< 0 = up to the highest slot used (at least 1)
  /// Universe discovery every this many packets (the rate times 10 s); 0 = never.
  std::uint32_t discovery_every = 0;
  std::vector<DmxActuator> actuators;
};

/// E1.31 data packets every tick (sequence numbers wrap 255 -> 0), universe discovery now and
/// then (to 239.255.250.214 when multicasting, else to the same destination), and three
/// stream-terminated packets when destroyed.
class SacnLink final : public NetworkDmxLink {
 public:
  /// Throws std::invalid_argument as DmxUniverse does, or for a universe outside 1..63999, a
  /// priority above 200; as UdpSender for the destination.
  explicit SacnLink(SacnLinkConfig config);
  ~SacnLink() override;
  SacnLink(const SacnLink&) = delete;
  SacnLink& operator=(const SacnLink&) = delete;

  std::uint64_t discovery_packets() const noexcept { return discovery_sent_; }

 private:
  std::size_t encode(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots) noexcept override;
  Status after_packet() noexcept override;

  SacnLinkConfig config_;
  sacn::DataHeader header_;
  std::unique_ptr<UdpSender> discovery_sender_;  ///< null: discovery goes through sender_
  std::vector<std::uint8_t> discovery_packet_;   ///< encoded once: the universe list never changes
  std::uint32_t since_discovery_ = 0;
  std::uint64_t discovery_sent_ = 0;
};

}  // namespace avar::firmware_iface
