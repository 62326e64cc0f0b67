#pragma once
// What a session publishes after every tick, and the ring that carries it out of the tick. A
// TickRecord is fixed-size: its per-channel and per-link rows live in arrays the ring allocated
// once, so writing one allocates nothing. The ring has one producer (the loop thread) and one
// consumer (the session's publisher); a full ring refuses the record and counts it as dropped.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/supervisor.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/session/command_queue.hpp"

namespace avar::session {

/// One channel at one tick, in channel units (NaN: unknown).
struct ChannelRecord {
  double target = 0;         ///< what the show (and the layers over it) asked for, before limits
  double command = 0;        ///< what the tick sent, after limits
  double reference = 0;      ///< the command the device carries out now (a link's command delay ago)
  double measured = 0;       ///< the feedback the tick read (from the previous exchange); NaN: none
  double temperature_c = 0;  ///< the device's newest report; NaN: none
  double load = 0;           ///< signed fraction of rated torque; NaN: none
  std::uint32_t device_faults = 0;
  bool held = false;  ///< a hold command has the channel
};

/// A command the tick took from the queue, and what became of it.
struct CommandRecord {
  Command command;
  CommandOutcome outcome = CommandOutcome::applied;
};

inline constexpr std::size_t kMaxCommandsPerTick = 8;

/// Where one of the show's inverse-kinematics targets was asked to be this tick.
struct TargetRecord {
  std::array<double, 3> point{};  ///< metres, the rig's base frame
  bool held = false;              ///< held by an aim command rather than following the show
};

struct TickRecord {
  std::uint64_t tick = 0;
  double now_s = 0;       ///< loop time
  double lateness_s = 0;  ///< wake-up lateness (0 on the stepped clock)
  control::Phase phase = control::Phase::disabled;
  double show_time_s = 0;       ///< show time of the last running tick
  bool paused = false;          ///< show time stands (pause, scrub, or the session started paused)
  bool looping = false;         ///< the show starts over at its end (the show's loop, or a loop command)
  bool estop = false;           ///< the session's e-stop was pressed by this tick
  bool stop_requested = false;  ///< a stop (command, Ctrl-C) asked the figure to ease to rest
  control::Fault fault;         ///< the latched fault (cause none: none)
  std::uint64_t faults_seen = 0;
  std::size_t command_count = 0;  ///< entries of `commands` used
  std::array<CommandRecord, kMaxCommandsPerTick> commands{};
  /// What each stage of this tick cost, nanoseconds, by control::Stage (0: not timed, as on
  /// the stepped clock).
  std::array<std::int64_t, control::kStageCount> stage_ns{};
  /// The show's targets, in its order (the first control::TargetAims::kCapacity of them).
  std::size_t target_count = 0;
  std::array<TargetRecord, control::TargetAims::kCapacity> targets{};
  std::span<ChannelRecord> channels;              ///< one per rig channel
  std::span<firmware_iface::LinkCounters> links;  ///< one per rig link, as of this tick
  /// Each live control's raw value as the tick read it, NaN before it first moved
  /// (SessionConfig::recorded_controls; empty without).
  std::span<double> controls;
};

class TickRing {
 public:
  /// `capacity` records (at least 2) of `channels` channels, `links` links and `controls` live
  /// controls. Allocates.
  TickRing(std::size_t capacity, std::size_t channels, std::size_t links, std::size_t controls);
  TickRing(const TickRing&) = delete;
  TickRing& operator=(const TickRing&) = delete;

  /// Producer: the slot to fill, or nullptr when the ring is full (counted as dropped).
  /// Real-time safe.
  TickRecord* claim() noexcept;
  /// Producer: makes the claimed slot visible to the consumer. Real-time safe.
  void publish() noexcept;

  /// Consumer: the oldest published record, or nullptr when there is none.
  const TickRecord* front() const noexcept;
  /// Consumer: frees the front record.
  void pop() noexcept;

  /// Consumer: a token for wait(), taken before looking at front().
  std::uint32_t signal() const noexcept { return signal_.load(std::memory_order_acquire); }
  /// Consumer: blocks until a record is published (or wake()) after signal() gave `token`.
  void wait(std::uint32_t token) const noexcept { signal_.wait(token, std::memory_order_acquire); }
  /// Wakes a waiting consumer (to stop it).
  void wake() noexcept {
    signal_.fetch_add(1, std::memory_order_release);
    signal_.notify_all();
  }
  std::uint64_t published() const noexcept { return published_.load(std::memory_order_acquire); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  std::size_t capacity() const noexcept { return slots_.size(); }

 private:
  std::vector<TickRecord> slots_;
  std::vector<ChannelRecord> channel_rows_;
  std::vector<firmware_iface::LinkCounters> link_rows_;
  std::vector<double> control_rows_;
  alignas(64) std::atomic<std::uint64_t> published_{0};  ///< records made visible, ever
  alignas(64) std::atomic<std::uint64_t> consumed_{0};   ///< records popped, ever
  std::atomic<std::uint64_t> dropped_{0};
  /// Bumped on every publish: what a waiting consumer sleeps on (a futex word; notifying costs a
  /// system call only while the consumer sleeps).
  std::atomic<std::uint32_t> signal_{0};
};

/// Watches a session: called with every record that reached the publisher, in tick order (on
/// the session's publisher thread in real time; on the caller's thread, right after the tick,
/// on the stepped clock). May take its time: the loop does not wait for it (in real time a ring
/// that fills drops records, counted in the session's result).
class SessionObserver {
 public:
  virtual ~SessionObserver() = default;
  virtual void on_tick(const TickRecord& record) = 0;
};

}  // namespace avar::session
