#include "avar/control/supervisor.hpp"

#include <algorithm>

namespace avar::control {

const char* to_string(Phase p) noexcept {
  switch (p) {
    case Phase::disabled: return "disabled";
    case Phase::homing: return "homing";
    case Phase::running: return "running";
    case Phase::stopping: return "stopping";
    case Phase::faulted: return "faulted";
  }
  return "unknown";
}

const char* to_string(FaultCause c) noexcept {
  switch (c) {
    case FaultCause::none: return "none";
    case FaultCause::estop: return "e-stop";
    case FaultCause::link_watchdog: return "link watchdog";
    case FaultCause::link_failure: return "link failure";
    case FaultCause::tracking_error: return "tracking error";
    case FaultCause::non_finite: return "non-finite command";
    case FaultCause::device_overheat: return "device over-temperature";
    case FaultCause::device_overload: return "device overload";
    case FaultCause::device_error: return "device hardware error";
    case FaultCause::device_lost: return "device lost";
    case FaultCause::deadline_budget: return "deadline misses over budget";
  }
  return "unknown";
}

Supervisor::Supervisor(const rig::Rig& rig, std::size_t link_count)
    : rig_(rig), channel_rests_(rig.channels.size(), 1), link_dead_(link_count, 0) {
  // A channel eases to rest on a fault unless none of its actuators asks for that.
  std::vector<char> has_actuator(rig.channels.size(), 0);
  for (const rig::ActuatorSpec& a : rig.actuators) {
    const std::size_t c = a.channel.value;
    if (!has_actuator[c]) channel_rests_[c] = 0;
    has_actuator[c] = 1;
    if (a.failsafe == rig::Failsafe::rest) channel_rests_[c] = 1;
  }
}

void Supervisor::enter(Phase p) noexcept {
  if (p == Phase::faulted) return;
  if (phase_ == Phase::faulted && p != Phase::disabled) return;  // motion resumes only after clear()
  phase_ = p;
}

bool Supervisor::latch(FaultCause cause, std::size_t index, double value, double now_s, Status status) noexcept {
  ++faults_seen_;
  if (fault_.cause != FaultCause::none) return false;  // the first fault stays latched
  fault_ = {cause, status, index, value, now_s, phase_};
  // Nothing was moving: latch, but do not start driving anything.
  drive_in_fault_ = phase_ != Phase::disabled;
  phase_ = Phase::faulted;
  return drive_in_fault_;
}

void Supervisor::failsafe_goal(std::span<const double> rest, std::span<const double> heading,
                               std::span<double> goal) const noexcept {
  for (std::size_t c = 0; c < goal.size(); ++c) goal[c] = channel_rests_[c] ? rest[c] : heading[c];
}

void Supervisor::release_failsafe(std::span<firmware_iface::ActuatorLink* const> links) const noexcept {
  for (const rig::ActuatorSpec& a : rig_.actuators)
    if (a.failsafe == rig::Failsafe::release && a.link.value < links.size())
      links[a.link.value]->release_channel(a.channel.value);
}

bool Supervisor::any_link_alive() const noexcept {
  for (char dead : link_dead_)
    if (!dead) return true;
  return false;
}

bool Supervisor::clear() noexcept {
  if (phase_ != Phase::faulted) return false;
  fault_ = {};
  std::fill(link_dead_.begin(), link_dead_.end(), 0);
  phase_ = Phase::disabled;
  return true;
}

}  // namespace avar::control
