#include "avar/firmware_iface/odrive_drives.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "avar/firmware_iface/can_conversation.hpp"

namespace avar::firmware_iface {
namespace {

namespace od = odrive;

std::string node_prefix(std::uint8_t node) { return "ODrive node " + std::to_string(node) + ": "; }

std::string hex(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", v);
  return text;
}

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

OdriveDrives::OdriveDrives(OdriveDrivesConfig config) : CanDrives(config.actuators), config_(std::move(config)) {
  std::fill(std::begin(axis_of_node_), std::end(axis_of_node_), kNoAxis);
  if (config_.heartbeat_budget_ticks == 0) throw std::invalid_argument("ODrive: heartbeat budget must be at least one tick");
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    const OdriveActuator& a = config_.actuators[i];
    const std::string who = "ODrive node " + std::to_string(a.node);
    if (a.node > od::kMaxNode) throw std::invalid_argument(who + ": node ID out of range 0..63");
    if (axis_of_node_[a.node] != kNoAxis) throw std::invalid_argument(who + ": node ID used twice");
    if (!positive_finite(a.velocity_limit)) throw std::invalid_argument(who + ": velocity limit must be positive (turns/s)");
    if (!positive_finite(a.current_limit)) throw std::invalid_argument(who + ": current limit must be positive (A)");
    if (a.input_mode != od::InputMode::passthrough && a.input_mode != od::InputMode::pos_filter &&
        a.input_mode != od::InputMode::trap_traj)
      throw std::invalid_argument(who + ": input mode must be passthrough, pos_filter or trap_traj");
    axis_of_node_[a.node] = static_cast<int>(i);
    Axis axis;
    axis.node = a.node;
    axis.heartbeat = DeviceWatch(config_.heartbeat_budget_ticks);
    axes_.push_back(axis);
  }
}

Status OdriveDrives::ask_position(FrameTransport& bus, std::size_t i, float* turns) {
  const std::uint8_t node = axes_[i].node;
  const std::uint32_t reply_id = od::can_id(node, od::kGetEncoderEstimates);
  od::EncoderEstimates e;
  auto match = [&](const CanFrame& f) { return f.id == reply_id && od::decode_encoder_estimates(f, &e); };
  if (const Status s = ask_frame(bus, od::encode_get_encoder_estimates(node), config_.reply_timeout, match); s != Status::ok)
    return s;
  if (!std::isfinite(e.position)) return Status::bad_data;
  *turns = e.position;
  return Status::ok;
}

Status OdriveDrives::start(FrameTransport& bus) {
  start_problem_.clear();
  bus.discard_input();  // heartbeats from before start may still carry errors since cleared
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    if (const Status s = start_axis(bus, i); s != Status::ok) {
      idle_axes(bus, i + 1);
      return s;
    }
  }
  return Status::ok;
}

Status OdriveDrives::start_axis(FrameTransport& bus, std::size_t i) {
  const OdriveActuator& a = config_.actuators[i];
  Axis& axis = axes_[i];
  const std::string who = node_prefix(a.node);
  auto send = [&](const CanFrame& f, const char* what) {
    const Status s = bus.send(std::span<const CanFrame>(&f, 1));
    if (s != Status::ok) start_problem_ = who + "sending " + what + " failed (" + std::string(to_string(s)) + ")";
    return s;
  };

  if (const Status s = send(od::encode_clear_errors(a.node), "Clear Errors"); s != Status::ok) return s;
  float present = 0;
  if (const Status s = ask_position(bus, i, &present); s != Status::ok) {
    start_problem_ = who + "no encoder estimate in answer to Get Encoder Estimates within " +
                     std::to_string(config_.reply_timeout.count()) + " ms (" + std::string(to_string(s)) + ")";
    return s;
  }
  if (const Status s =
          send(od::encode_set_controller_modes(a.node, od::ControlMode::position, a.input_mode), "Set Controller Modes");
      s != Status::ok)
    return s;
  if (const Status s = send(
          od::encode_set_limits(a.node, static_cast<float>(a.velocity_limit), static_cast<float>(a.current_limit)), "Set Limits");
      s != Status::ok)
    return s;
  // Hold where the axis is: closed loop starts without a jump.
  if (const Status s = send(od::encode_set_input_pos(a.node, present), "Set Input Pos"); s != Status::ok) return s;
  axes_[i].last_turns = present;
  if (const Status s = send(od::encode_set_axis_state(a.node, od::AxisState::closed_loop_control), "Set Axis Requested State");
      s != Status::ok)
    return s;

  // Heartbeats that still show IDLE may predate the request; an axis error means it was refused.
  const std::uint32_t heartbeat_id = od::can_id(a.node, od::kHeartbeat);
  bool seen = false, refused = false;
  od::Heartbeat last;
  auto match = [&](const CanFrame& f) {
    od::Heartbeat h;
    if (f.id != heartbeat_id || !od::decode_heartbeat(f, config_.heartbeat_layout, &h)) return false;
    seen = true;
    last = h;
    refused = h.axis_error != 0;
    return refused || (h.in_state(od::AxisState::closed_loop_control));
  };
  const Status s = await_frame(bus, config_.closed_loop_timeout, match);
  if (s == Status::ok && !refused) {
    axis.last_heartbeat = last;
    axis.heartbeat_seen = true;
    axis.heartbeat.answered();
    ChannelTelemetry& t = table().telemetry(i);
    t.position = table().to_channel(i, present);
    t.faults = 0;
    return Status::ok;
  }
  start_problem_ = who + "did not enter CLOSED_LOOP_CONTROL";
  if (s == Status::io_error) {
    start_problem_ += " (I/O error on the bus)";
    return s;
  }
  if (!seen) {
    start_problem_ += ": no heartbeat within " + std::to_string(config_.closed_loop_timeout.count()) + " ms";
    return Status::timeout;
  }
  start_problem_ += refused ? "; its heartbeat said: "
                            : " within " + std::to_string(config_.closed_loop_timeout.count()) + " ms; its last heartbeat said: ";
  start_problem_ += "axis error " + hex(last.axis_error);
  if (last.axis_error != 0 && config_.heartbeat_layout == od::HeartbeatLayout::v0_5)
    start_problem_ += " (" + od::describe_axis_error(last.axis_error) + ")";
  start_problem_ += ", state " + od::describe_axis_state(last.state);
  return refused ? Status::bad_data : Status::timeout;
}

void OdriveDrives::idle_axes(FrameTransport& bus, std::size_t count) {
  for (std::size_t i = 0; i < count && i < axes_.size(); ++i) {
    const CanFrame f = od::encode_set_axis_state(axes_[i].node, od::AxisState::idle);
    static_cast<void>(bus.send(std::span<const CanFrame>(&f, 1)));
  }
}

Status OdriveDrives::read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) {
  Status result = Status::ok;
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    float turns = 0;
    if (const Status s = ask_position(bus, i, &turns); s != Status::ok) {
      if (result == Status::ok || s == Status::io_error) result = s;
      continue;
    }
    frame[table().channel(i)] = table().to_channel(i, turns);
    known[table().channel(i)] = true;
  }
  return result;
}

std::size_t OdriveDrives::max_tick_frames() const noexcept {
  return axes_.size() * (config_.readback == OdriveReadback::rtr ? 2 : 1);
}

void OdriveDrives::encode_tick(std::span<const double> frame, CanOutbox& out) noexcept {
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    Axis& axis = axes_[i];
    axis.estimate_asked = false;
    axis.estimate_taken = false;
    if (table().released(i)) {
      axis.last_turns = std::numeric_limits<double>::quiet_NaN();
      if (table().release_pending(i) && out.push(od::encode_set_axis_state(axis.node, od::AxisState::idle)))
        table().set_release_told(i);
      continue;
    }
    const double turns = table().to_device(i, frame);
    const double vel_ff =
        config_.tick_period_s > 0 && std::isfinite(axis.last_turns) ? (turns - axis.last_turns) / config_.tick_period_s : 0.0;
    axis.last_turns = turns;
    if (!out.push(od::encode_set_input_pos(axis.node, static_cast<float>(turns), vel_ff))) continue;
    if (config_.readback == OdriveReadback::rtr) axis.estimate_asked = out.push(od::encode_get_encoder_estimates(axis.node));
  }
}

bool OdriveDrives::take(const CanFrame& f) noexcept {
  if (f.error || f.extended || f.rtr || f.id > kCanMaxStandardId) return false;
  const int index = axis_of_node_[od::odrive_node(f.id)];
  if (index == kNoAxis) return false;
  const auto i = static_cast<std::size_t>(index);
  switch (od::odrive_command(f.id)) {
    case od::kHeartbeat: {
      od::Heartbeat h;
      if (!od::decode_heartbeat(f, config_.heartbeat_layout, &h)) return false;
      take_heartbeat(i, h);
      return true;
    }
    case od::kGetEncoderEstimates: {
      od::EncoderEstimates e;
      if (!od::decode_encoder_estimates(f, &e) || !std::isfinite(e.position)) return false;
      ChannelTelemetry& t = table().telemetry(i);
      t.position = table().to_channel(i, e.position);
      ++t.updates;
      axes_[i].estimate_taken = true;
      return true;
    }
    default: return false;
  }
}

void OdriveDrives::take_heartbeat(std::size_t i, const od::Heartbeat& h) noexcept {
  Axis& axis = axes_[i];
  axis.last_heartbeat = h;
  axis.heartbeat_seen = true;
  axis.heartbeat_this_tick = true;
  if (h.axis_error != 0) device_errors_.fetch_add(1, std::memory_order_relaxed);
  std::uint32_t faults = 0;
  if (h.axis_error != 0)
    faults |= config_.heartbeat_layout == od::HeartbeatLayout::v0_5 ? od::axis_error_faults(h.axis_error) : kDeviceOther;
  if (h.motor_error) faults |= kDeviceElectrical;
  if (h.encoder_error) faults |= kDeviceEncoder;
  if (h.controller_error) faults |= kDeviceOther;
  // A released axis is meant to be idle; a driven one must stay in closed loop.
  const bool driven = !table().released(i);
  if (h.axis_error != 0 || (driven && !h.in_state(od::AxisState::closed_loop_control))) faults |= kDeviceFaultState;
  table().telemetry(i).faults = faults;  // it answered: no longer lost
}

bool OdriveDrives::replies_complete() const noexcept {
  // An axis that missed its last two estimates is still asked but not waited for (a drive off
  // the bus must not stall every tick until its heartbeat budget runs out).
  return std::all_of(axes_.begin(), axes_.end(),
                     [](const Axis& a) { return !a.estimate_asked || a.estimate_taken || a.estimates.lost(); });
}

Status OdriveDrives::settle() noexcept {
  bool complete = true;
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    Axis& axis = axes_[i];
    if (axis.estimate_asked && !axis.estimate_taken) {
      complete = false;
      axis.estimates.missed();
    } else if (axis.estimate_taken) {
      axis.estimates.answered();
    }
    if (!axis.estimate_taken) table().forget_feedback(i);
    // Heartbeats count from one settle to the next: those taken before this tick's frames
    // went out (they arrived between ticks) count too.
    if (axis.heartbeat_this_tick) axis.heartbeat.answered();
    else if (axis.heartbeat.missed()) table().telemetry(i).faults |= kDeviceLost;
    axis.heartbeat_this_tick = false;
  }
  return complete ? Status::ok : Status::timeout;
}

void OdriveDrives::encode_release(CanOutbox& out) noexcept {
  for (const Axis& axis : axes_) static_cast<void>(out.push(od::encode_set_axis_state(axis.node, od::AxisState::idle)));
  table().release_all_told();
}

std::string OdriveDrives::axis_problem(std::size_t i) const {
  const Axis& axis = axes_[i];
  const std::string who = node_prefix(axis.node);
  if (axis.heartbeat.lost()) return who + "no heartbeat for " + std::to_string(axis.heartbeat.silent_ticks()) + " ticks";
  if (!axis.heartbeat_seen) return {};
  const od::Heartbeat& h = axis.last_heartbeat;
  const bool closed_loop = h.in_state(od::AxisState::closed_loop_control);
  if (h.axis_error == 0 && (closed_loop || table().released(i))) return {};
  std::string out = who;
  if (h.axis_error != 0) {
    out += "axis error " + hex(h.axis_error);
    if (config_.heartbeat_layout == od::HeartbeatLayout::v0_5) out += " (" + od::describe_axis_error(h.axis_error) + ")";
    out += ", ";
  }
  out += "state " + od::describe_axis_state(h.state);
  if (h.axis_error == 0) out += ", not CLOSED_LOOP_CONTROL";
  for (const auto& [flag, name] :
       {std::pair{h.motor_error, "motor"}, {h.encoder_error, "encoder"}, {h.controller_error, "controller"}})
    if (flag) out += std::string(", ") + name + " error flagged";
  return out;
}

std::string OdriveDrives::channel_problem(std::size_t channel) const {
  std::string out;
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    if (table().channel(i) != channel) continue;
    const std::string problem = axis_problem(i);
    if (problem.empty()) continue;
    if (!out.empty()) out += "; ";
    out += problem;
  }
  return out;
}

}  // namespace avar::firmware_iface
