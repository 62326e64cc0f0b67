#pragma once
// A simulated classic CAN bus: borrowed CanNodes (simulated drives) plus one host port (the
// controller of the host's adapter), on a simulated clock, in the caller's thread. Frames are
// arbitrated as on a real bus: among everything pending (the host's queue included) the one
// whose arbitration field is lowest goes next (lower identifier; at equal base identifier a
// standard frame before an extended one and a data frame before a remote one). When the host
// and a node offer the very same arbitration field, the host's frame goes first (a real bus
// would make both transmitters see a bit error; the simulator does not model that collision).
// Every frame is heard by every attached node but its sender, and by the host port.
//
// Timing, one of two:
// - wire: each frame occupies the bus for can_frame_bits(frame) / bitrate seconds and the
//   clock moves by it; nodes advance with the clock (SimCanTransport runs the bus this way).
// - instant: frames are delivered the moment they are offered; the clock moves only in
//   run_until() across idle time (the simulated SLCAN adapter, whose serial link is the
//   bottleneck, runs the bus this way). Load figures still count each frame's wire time.
// In both, idle time passes in steps of at most idle_step_s, so that frames a node starts
// between two steps (cyclic messages, delayed replies) go out at most one step late.
//
// Faults: error frames for the host (inject_error), a host controller that goes bus-off (it
// hears nothing, its queued frames are lost and it can send nothing until restart_host()),
// nodes dropping off the bus (a detached node hears and says nothing; frames it queues are lost;
// its own time still runs).
//
// Not thread-safe. Allocates only when nodes are added; running the bus allocates nothing.
// Nodes' exceptions pass through run_until().

#include <cstddef>
#include <cstdint>
#include <vector>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::sim {

enum class SimCanTiming { wire, instant };

struct SimCanBusConfig {
  int bitrate = 1'000'000;  ///< bit/s
  SimCanTiming timing = SimCanTiming::wire;
  double idle_step_s = 1e-4;            ///< longest step of idle time (> 0)
  std::size_t host_tx_capacity = 256;   ///< frames the host may have queued for the bus
  std::size_t host_rx_capacity = 1024;  ///< frames waiting for the host; more are lost (overrun)
};

/// What the bus carried since it was made or since reset_statistics().
struct SimCanBusStatistics {
  std::uint64_t frames = 0;         ///< data and remote frames put on the wire
  std::uint64_t bits = 0;           ///< their worst-case bits (can_frame_bits)
  double busy_s = 0;                ///< their wire time, bits / bitrate
  double elapsed_s = 0;             ///< simulated time
  std::uint64_t host_frames = 0;    ///< frames of those the host sent
  std::uint64_t host_overruns = 0;  ///< frames lost because the host's receive queue was full
  /// busy / elapsed (0 before any time passed). In instant timing it may exceed 1: the frames
  /// were more than the bus could have carried in that time.
  double load() const noexcept { return elapsed_s > 0 ? busy_s / elapsed_s : 0; }
};

class SimCanBus {
 public:
  /// Nodes are borrowed (null entries ignored) and must outlive the bus; all start attached.
  explicit SimCanBus(SimCanBusConfig config = {}, const std::vector<CanNode*>& nodes = {});

  /// Adds a node (attached). Not real-time.
  void add_node(CanNode& node);
  /// Takes a node off the bus (false: it hears and says nothing, and every frame it queues is
  /// dropped) or puts it back (true). Unknown nodes are ignored.
  void set_attached(const CanNode& node, bool attached) noexcept;
  bool attached(const CanNode& node) const noexcept;

  // ---- the host port ----
  /// Queues a frame for the bus. ok; out_of_range for an invalid or error frame; io_error while
  /// the host is bus-off or offline; timeout when the host's transmit queue is full.
  Status host_send(const firmware_iface::CanFrame& frame) noexcept;
  /// Takes the oldest frame (or error frame) for the host; its timestamp is the bus time (ns)
  /// at the end of the frame. False when there is none.
  bool host_receive(firmware_iface::CanFrame* frame) noexcept;
  std::size_t host_pending() const noexcept { return rx_count_; }
  /// Frames the host queued that are not yet on the wire (wire timing: one in flight counts).
  std::size_t host_unsent() const noexcept { return tx_count_ + (in_flight_ && in_flight_from_host_ ? 1 : 0); }
  void host_discard() noexcept { rx_first_ = rx_count_ = 0; }
  /// An offline host (an adapter that is closed) neither hears nor sends; its queues are
  /// emptied.
  void set_host_online(bool online) noexcept;
  bool host_online() const noexcept { return host_online_; }
  bool host_bus_off() const noexcept { return host_bus_off_; }
  /// Brings the host's controller back after a bus-off (what a reopen does).
  void restart_host() noexcept { host_bus_off_ = false; }

  // ---- faults ----
  /// The host receives an error frame with these CanErrorClass bits (kCanErrorBusOff among
  /// them also puts the host bus-off, as inject_bus_off()).
  void inject_error(std::uint32_t classes) noexcept;
  /// The host's controller goes bus-off: it receives a kCanErrorBusOff error frame, its queued
  /// frames are lost, it hears nothing and its sends fail until restart_host().
  void inject_bus_off() noexcept;

  // ---- running ----
  enum class Until {
    time,        ///< run to the end time
    host_frame,  ///< stop as soon as a frame for the host is waiting
    host_sent,   ///< stop once the host's queue is empty and its last frame off the wire
  };
  /// Runs the bus (and the nodes' time) until `end_s` on the bus clock or the condition;
  /// returns whether the condition held (Until::time: always true). In wire timing a frame on
  /// the wire at end_s finishes on the next run. run_until(now_s()) delivers, in instant
  /// timing, everything pending and every reply to it without moving the clock.
  bool run_until(double end_s, Until until = Until::time);

  double now_s() const noexcept { return now_s_; }
  int bitrate() const noexcept { return config_.bitrate; }
  SimCanTiming timing() const noexcept { return config_.timing; }
  /// Wire time of one frame on this bus, seconds.
  double frame_seconds(const firmware_iface::CanFrame& frame) const noexcept {
    return firmware_iface::can_frame_bits(frame) / static_cast<double>(config_.bitrate);
  }

  SimCanBusStatistics statistics() const noexcept;
  /// Starts a new measurement window (counts to 0, elapsed from now).
  void reset_statistics() noexcept;

 private:
  struct Node {
    CanNode* node = nullptr;
    bool attached = true;
  };
  /// The winner of arbitration among the pending frames: a node index, kHost, or kNone.
  static constexpr std::size_t kHost = static_cast<std::size_t>(-1);
  static constexpr std::size_t kNone = static_cast<std::size_t>(-2);
  std::size_t arbitrate(firmware_iface::CanFrame* frame);
  /// Puts the winner's frame on the wire (in flight, or delivered at once in instant timing).
  void start(std::size_t sender, const firmware_iface::CanFrame& frame);
  /// Everyone but the sender hears it.
  void deliver(std::size_t sender, const firmware_iface::CanFrame& frame);
  void to_host(const firmware_iface::CanFrame& frame) noexcept;
  void advance_nodes(double dt_s);
  bool done(Until until) const noexcept;
  void drop_detached_frames();

  SimCanBusConfig config_;
  std::vector<Node> nodes_;
  double now_s_ = 0;

  std::vector<firmware_iface::CanFrame> tx_;  ///< host's transmit ring (capacity fixed)
  std::size_t tx_first_ = 0, tx_count_ = 0;
  std::vector<firmware_iface::CanFrame> rx_;  ///< host's receive ring (capacity fixed)
  std::size_t rx_first_ = 0, rx_count_ = 0;
  bool host_online_ = true;
  bool host_bus_off_ = false;

  bool in_flight_ = false;  ///< wire timing: a frame is on the wire
  bool in_flight_from_host_ = false;
  std::size_t in_flight_sender_ = kNone;
  firmware_iface::CanFrame in_flight_frame_;
  double in_flight_end_s_ = 0;

  SimCanBusStatistics stats_;
  double stats_start_s_ = 0;
};

}  // namespace avar::sim
