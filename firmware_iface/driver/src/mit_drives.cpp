#include "avar/firmware_iface/mit_drives.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "avar/firmware_iface/can_conversation.hpp"

namespace avar::firmware_iface {
namespace {

std::string mit_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

std::string mit_motor(std::uint32_t node) { return "MIT motor " + std::to_string(node); }

std::uint8_t mit_reply_id(std::uint32_t node, const mit::MitReplyFormat& format) {
  return static_cast<std::uint8_t>(node & 0xFFu & format.id_mask);
}

bool mit_finite_within(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }

void mit_check_actuator(const MitActuator& a, std::uint32_t master_id) {
  const std::string who = mit_motor(a.node);
  auto invalid = [&](const std::string& what) { throw std::invalid_argument(who + ": " + what); };
  if (a.node < 1 || a.node > kCanMaxStandardId) invalid("CAN_ID must be 1..0x7FF");
  if (a.node == master_id) invalid("CAN_ID is the master ID its replies go to");
  const mit::MitRanges& r = a.ranges;
  if (!r.valid()) invalid("ranges need finite bounds, each min below its max, kp_max and kd_max above 0");
  if (!mit_finite_within(a.kp, 0, r.kp_max)) invalid("kp " + mit_number(a.kp) + " is outside 0.." + mit_number(r.kp_max));
  if (!mit_finite_within(a.kd, 0, r.kd_max)) invalid("kd " + mit_number(a.kd) + " is outside 0.." + mit_number(r.kd_max));
  const LinearCalibration& c = a.calibration;
  if (!std::isfinite(c.channel_min) || !std::isfinite(c.channel_max) || !(c.channel_max > c.channel_min) ||
      !std::isfinite(c.device_at_min) || !std::isfinite(c.device_at_max) || !std::isfinite(c.trim) ||
      c.device_at_min == c.device_at_max)
    invalid("calibration needs finite ends, channel_max above channel_min and two different device ends");
  if (c.device_low() < r.p_min || c.device_high() > r.p_max)
    invalid("calibrated window " + mit_number(c.device_low()) + ".." + mit_number(c.device_high()) +
            " rad leaves the position range " + mit_number(r.p_min) + ".." + mit_number(r.p_max) + " rad");
}

const MitDrivesConfig& mit_checked(const MitDrivesConfig& config) {
  if (config.master_id > kCanMaxStandardId) throw std::invalid_argument("MIT motors: the master ID must be 0..0x7FF");
  if (config.reply_budget_ticks < 1) throw std::invalid_argument("MIT motors: the reply budget must be at least one tick");
  const auto& all = config.actuators;
  for (std::size_t i = 0; i < all.size(); ++i) {
    mit_check_actuator(all[i], config.master_id);
    for (std::size_t j = 0; j < i; ++j) {
      if (all[j].node == all[i].node) throw std::invalid_argument(mit_motor(all[i].node) + " is configured twice");
      if (mit_reply_id(all[j].node, config.reply_format) == mit_reply_id(all[i].node, config.reply_format))
        throw std::invalid_argument("MIT motors " + std::to_string(all[j].node) + " and " + std::to_string(all[i].node) +
                                    " cannot be told apart: both reply with ID " +
                                    std::to_string(mit_reply_id(all[i].node, config.reply_format)) + " in byte 0");
    }
  }
  return config;
}

}  // namespace

MitDrives::MitDrives(MitDrivesConfig config) : CanDrives(mit_checked(config).actuators), config_(std::move(config)) {
  motors_.resize(config_.actuators.size());
  for (std::size_t i = 0; i < motors_.size(); ++i)
    motors_[i] = new_motor(mit_reply_id(config_.actuators[i].node, config_.reply_format));
}

MitDrives::Motor MitDrives::new_motor(std::uint8_t reply_id) const noexcept {
  Motor m;
  m.reply_id = reply_id;
  m.replies = DeviceWatch(config_.reply_budget_ticks);
  return m;
}

std::string MitDrives::motor_name(std::size_t i) const { return mit_motor(config_.actuators[i].node); }

CanFrame MitDrives::hold_frame(std::size_t i) const noexcept {
  const MitActuator& a = config_.actuators[i];
  return mit::command_frame(a.node, {motors_[i].command, 0, a.kp, a.kd, 0}, a.ranges);
}

bool MitDrives::is_reply_of(const CanFrame& f, std::size_t i, mit::MitReply* reply) const noexcept {
  if (f.error || f.rtr || f.extended || f.id != config_.master_id) return false;
  return mit::decode_reply(f.payload(), config_.actuators[i].ranges, config_.reply_format, reply) &&
         reply->id == motors_[i].reply_id;
}

void MitDrives::record_reply(std::size_t i, const mit::MitReply& reply) noexcept {
  ChannelTelemetry& t = table().telemetry(i);
  t.position = table().to_channel(i, reply.position);
  // The torque limit is t_max for the symmetric ranges every model uses; the larger bound keeps
  // the fraction's sign and scale for odd ones.
  const mit::MitRanges& r = config_.actuators[i].ranges;
  t.load = std::clamp(reply.torque / std::max(std::abs(r.t_min), std::abs(r.t_max)), -1.0, 1.0);
  t.faults &= ~static_cast<std::uint32_t>(kDeviceLost);
  ++t.updates;
  motors_[i].replies.answered();
}

void MitDrives::exit_started(FrameTransport& bus) {
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    if (!motors_[i].started) continue;
    const CanFrame exit = mit::special_frame(config_.actuators[i].node, mit::MitFrameKind::exit_motor_mode);
    (void)bus.send(std::span<const CanFrame>(&exit, 1));  // best effort: the start has failed already
    motors_[i].started = false;
  }
}

Status MitDrives::start(FrameTransport& bus) {
  start_problem_.clear();
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    motors_[i] = new_motor(motors_[i].reply_id);
    table().telemetry(i) = {};
  }
  const std::string within = " within " + std::to_string(config_.start_timeout.count()) + " ms";
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    const MitActuator& a = config_.actuators[i];
    mit::MitReply reply;
    auto answers = [&](const CanFrame& f) { return is_reply_of(f, i, &reply); };
    auto fail = [&](Status s, const std::string& what) {
      start_problem_ = motor_name(i) + ": " + (s == Status::io_error ? "the bus failed " + what : "no reply " + what + within);
      exit_started(bus);
      return s;
    };
    // Motor mode starts with cleared commands (no torque); its reply says where the motor is.
    motors_[i].started = true;
    const CanFrame enter = mit::special_frame(a.node, mit::MitFrameKind::enter_motor_mode);
    if (const Status s = ask_frame(bus, enter, config_.start_timeout, answers); s != Status::ok)
      return fail(s, "to enter motor mode");
    const LinearCalibration& cal = a.calibration;
    const double quantum = (a.ranges.p_max - a.ranges.p_min) / 65535.0;
    if (reply.position < cal.device_low() - quantum || reply.position > cal.device_high() + quantum) {
      start_problem_ = motor_name(i) + ": at " + mit_number(reply.position) + " rad, outside its calibrated window " +
                       mit_number(cal.device_low()) + ".." + mit_number(cal.device_high()) + " rad";
      exit_started(bus);
      return Status::out_of_range;
    }
    motors_[i].command = std::clamp(reply.position, cal.device_low(), cal.device_high());
    if (const Status s = ask_frame(bus, hold_frame(i), config_.start_timeout, answers); s != Status::ok)
      return fail(s, "to its first command (hold at " + mit_number(motors_[i].command) + " rad)");
    record_reply(i, reply);
  }
  return Status::ok;
}

Status MitDrives::read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) {
  Status result = Status::ok;
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    const MitActuator& a = config_.actuators[i];
    // Driven motors get their last command again; the others an exit, which a motor in menu mode ignores.
    const bool holding = motors_[i].started && !table().released(i);
    const CanFrame ask = holding ? hold_frame(i) : mit::special_frame(a.node, mit::MitFrameKind::exit_motor_mode);
    mit::MitReply reply;
    const Status s = ask_frame(bus, ask, config_.start_timeout, [&](const CanFrame& f) { return is_reply_of(f, i, &reply); });
    if (s != Status::ok) {
      result = s;
      continue;
    }
    record_reply(i, reply);
    frame[a.channel] = table().to_channel(i, reply.position);
    known[a.channel] = true;
  }
  return result;
}

void MitDrives::encode_tick(std::span<const double> frame, CanOutbox& out) noexcept {
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    Motor& m = motors_[i];
    m.expected = m.replied = false;
    if (table().released(i)) {
      if (table().release_pending(i) &&
          out.push(mit::special_frame(config_.actuators[i].node, mit::MitFrameKind::exit_motor_mode))) {
        table().set_release_told(i);
        m.started = false;
        m.expected = true;
      }
      continue;
    }
    m.command = table().to_device(i, frame);
    m.expected = out.push(hold_frame(i));
  }
}

bool MitDrives::take(const CanFrame& frame) noexcept {
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    mit::MitReply reply;
    if (!is_reply_of(frame, i, &reply)) continue;
    // A reply to a frame of an earlier tick is stale: it is ours, but not used.
    if (motors_[i].expected) {
      record_reply(i, reply);
      motors_[i].replied = true;
    }
    return true;
  }
  return false;
}

bool MitDrives::replies_complete() const noexcept {
  return std::all_of(motors_.begin(), motors_.end(),
                     [](const Motor& m) { return !m.expected || m.replied || m.replies.silent_ticks() >= kStopWaitingAfter; });
}

Status MitDrives::settle() noexcept {
  bool complete = true;
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    Motor& m = motors_[i];
    if (m.expected && m.replied) continue;
    table().forget_feedback(i);  // stale feedback is absent
    if (!m.expected) continue;   // released and told: not asked, not silent
    complete = false;
    if (m.replies.missed()) table().telemetry(i).faults |= kDeviceLost;
  }
  return complete ? Status::ok : Status::timeout;
}

void MitDrives::encode_release(CanOutbox& out) noexcept {
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    Motor& m = motors_[i];
    m.replied = false;
    m.expected = out.push(mit::special_frame(config_.actuators[i].node, mit::MitFrameKind::exit_motor_mode));
    m.started = false;
  }
  table().release_all_told();
}

std::string MitDrives::channel_problem(std::size_t channel) const {
  std::string problem;
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    if (table().channel(i) != channel || !motors_[i].replies.lost()) continue;
    if (!problem.empty()) problem += "; ";
    problem += motor_name(i) + ": no reply for " + std::to_string(motors_[i].replies.silent_ticks()) + " ticks";
  }
  return problem;
}

}  // namespace avar::firmware_iface
