#pragma once
// A simulated network DMX node (an Art-Net or sACN receiver) on a UDP socket of its own on
// loopback: it decodes every datagram with avar's decoders, keeps the universe it listens to,
// counts what it takes and what it refuses (malformed packets, other universes, packets out of
// sequence), and answers ArtPoll with an ArtPollReply as an Art-Net node must. Bad packets never
// change the universe.
//
// Sequence rule (E1.31 6.7.2, applied to Art-Net's sequence too when it is not 0): a packet
// whose sequence number is behind the last one by 1..19 is out of order and dropped.
// Not thread-safe: one thread calls everything. Not real-time (tests and the simulator's step).

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace avar::sim {

enum class DmxNodeProtocol { artnet, sacn };

struct SimDmxNodeConfig {
  DmxNodeProtocol protocol = DmxNodeProtocol::artnet;
  /// The universe the node outputs: an Art-Net Port-Address (0..32767) or an sACN universe.
  std::uint16_t universe = 0;
  std::uint16_t port = 0;  ///< UDP port on 127.0.0.1; 0 = any free one
  std::string short_name = "avar sim node";
};

struct SimDmxNodeCounters {
  std::uint64_t datagrams = 0;
  std::uint64_t bytes = 0;
  std::uint64_t packets = 0;         ///< data packets taken into the universe
  std::uint64_t bad_packets = 0;     ///< malformed, or of a protocol the node does not speak
  std::uint64_t other_universe = 0;  ///< well-formed data for another universe
  std::uint64_t out_of_order = 0;
  std::uint64_t polls_answered = 0;
  std::uint64_t discovery = 0;   ///< sACN universe discovery packets
  std::uint64_t terminated = 0;  ///< sACN packets with Stream_Terminated (not applied)
};

class SimDmxNode {
 public:
  /// Binds the socket; throws std::runtime_error when it cannot.
  explicit SimDmxNode(SimDmxNodeConfig config);
  ~SimDmxNode();
  SimDmxNode(const SimDmxNode&) = delete;
  SimDmxNode& operator=(const SimDmxNode&) = delete;

  /// "127.0.0.1:PORT".
  std::string endpoint() const;
  std::uint16_t port() const { return port_; }

  /// Takes in every datagram waiting, then keeps taking them in until `bytes` bytes were received
  /// since start or `timeout` passed; true when they were.
  bool receive_until(std::uint64_t bytes, std::chrono::milliseconds timeout);
  /// Handles one datagram as if it had come from 127.0.0.1:`from_port` (tests, fuzzing).
  void handle(std::span<const std::uint8_t> datagram, std::uint16_t from_port = 0);

  /// Slot value, 1-based DMX address; 0 for slots never sent.
  std::uint8_t slot(int address) const { return universe_[static_cast<std::size_t>(address - 1)]; }
  /// An 8-bit level, or a 16-bit one from the coarse slot at `address` and the fine slot after.
  int level(int address, bool fine) const { return fine ? slot(address) << 8 | slot(address + 1) : slot(address); }
  std::size_t slot_count() const { return slot_count_; }
  const SimDmxNodeCounters& counters() const { return counters_; }
  /// sACN: the priority and source name of the last packet taken.
  std::uint8_t priority() const { return priority_; }
  const std::string& source_name() const { return source_name_; }

 private:
  bool in_sequence(std::uint8_t sequence);
  void take(std::span<const std::uint8_t> slots);
  void answer_poll(std::uint16_t to_port);

  SimDmxNodeConfig config_;
  int fd_ = -1;
  std::uint16_t port_ = 0;
  std::array<std::uint8_t, 512> universe_{};
  std::size_t slot_count_ = 0;
  bool have_sequence_ = false;
  std::uint8_t last_sequence_ = 0;
  std::uint8_t priority_ = 0;
  std::string source_name_;
  SimDmxNodeCounters counters_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace avar::sim
