#pragma once
// The supervisor: the loop's states, the fault latch and the fail-safe bookkeeping, apart from
// the motion. The controller asks it what state the loop is in, tells it the transitions and the
// faults it sees, and carries out the fail-safe moves it prescribes:
//
//   disabled --begin--> homing --soft start done--> running --show over / stop--> stopping
//   stopping --at rest--> disabled;  any state --fault--> faulted --reset--> disabled
//
// Construction allocates; everything else is real-time safe: no allocation, exception, lock,
// string lookup or logging. Used from the loop thread only.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/rig/rig.hpp"

namespace avar::control {

enum class Phase { disabled, homing, running, stopping, faulted };
const char* to_string(Phase p) noexcept;

enum class FaultCause {
  none,
  estop,            ///< the e-stop input
  link_watchdog,    ///< a link completed no send within its watchdog time
  link_failure,     ///< a link reported an I/O error
  tracking_error,   ///< measured position too far from the command (channel)
  non_finite,       ///< a NaN or infinity reached the limiter (channel)
  device_overheat,  ///< a device reported over-temperature (channel)
  device_overload,  ///< a device reported overload (channel)
  device_error,     ///< a device reported another hardware error or its fault state (channel)
  device_lost,      ///< a device stopped answering: heartbeats or replies missed past budget (channel)
  deadline_budget,  ///< more deadline misses than allowed
};
const char* to_string(FaultCause c) noexcept;

/// The first fault, latched until reset.
struct Fault {
  FaultCause cause = FaultCause::none;
  Status status = Status::ok;
  std::size_t index = 0;         ///< channel or link, by cause
  double value = 0;              ///< the offending measurement where there is one (error, misses)
  double time_s = 0;             ///< loop time at which it was detected
  Phase from = Phase::disabled;  ///< the state the fault interrupted
};

class Supervisor {
 public:
  /// The rig's actuators give each channel's fail-safe action; link_count links are watched.
  Supervisor(const rig::Rig& rig, std::size_t link_count);

  Phase phase() const noexcept { return phase_; }
  const Fault& latched_fault() const noexcept { return fault_; }
  /// Every fault reported, the latched one included.
  std::uint64_t faults_seen() const noexcept { return faults_seen_; }
  /// The latched fault interrupted motion, so its fail-safe moves are to be driven.
  bool driving_failsafe() const noexcept { return phase_ == Phase::faulted && drive_in_fault_; }
  /// Whether a tick has anything to drive: homing, running, stopping, or fail-safe moves.
  bool drives() const noexcept { return phase_ != Phase::disabled && (phase_ != Phase::faulted || drive_in_fault_); }

  /// A transition of the motion (homing, running, stopping, disabled). Faulted is entered by
  /// latch() only, and left for motion only through clear(); entering disabled from it (every
  /// actuator released at once) keeps the fault latched.
  void enter(Phase p) noexcept;

  /// Latches a fault at loop time now_s: the first one wins and is kept with the state it
  /// interrupted; later ones are only counted. Works from every state (an e-stop while idle
  /// latches, but nothing starts moving). Returns true when the caller must start the fail-safe
  /// actions: this fault is the first and it interrupted motion.
  bool latch(FaultCause cause, std::size_t index, double value, double now_s, Status status) noexcept;

  /// The fail-safe moves' goal: a channel eases to rest when one of its actuators asks for "rest"
  /// (or it has none), and holds where it was heading otherwise. Spans are indexed by channel.
  void failsafe_goal(std::span<const double> rest, std::span<const double> heading, std::span<double> goal) const noexcept;
  /// Stops driving every actuator whose fail-safe action is "release"; links[i] serves link i.
  void release_failsafe(std::span<firmware_iface::ActuatorLink* const> links) const noexcept;

  /// A link that can send no more: its actuators keep their last command (or the device's own
  /// fail-safe).
  void link_died(std::size_t link) noexcept { link_dead_[link] = 1; }
  bool link_dead(std::size_t link) const noexcept { return link_dead_[link] != 0; }
  bool any_link_alive() const noexcept;

  /// faulted -> disabled, clearing the fault and the dead links. The caller checks that the
  /// fail-safe moves are over. Returns false (and changes nothing) when not faulted.
  bool clear() noexcept;

 private:
  const rig::Rig& rig_;
  std::vector<char> channel_rests_;  ///< per channel: some actuator's fail-safe is "rest"
  std::vector<char> link_dead_;
  Phase phase_ = Phase::disabled;
  Fault fault_;
  std::uint64_t faults_seen_ = 0;
  bool drive_in_fault_ = false;
};

}  // namespace avar::control
