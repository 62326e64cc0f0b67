#include "avar/sim/sim_ssc32.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "avar/firmware_iface/wire_time.hpp"
#include "avar/sim/reply_queue.hpp"

namespace avar::sim {
namespace ssc = firmware_iface::ssc32;

SimSsc32::SimSsc32(SimSsc32Config config) : config_(config) {
  if (config_.baud != 9600 && config_.baud != 38400 && config_.baud != 115200)
    throw std::invalid_argument("an SSC-32U runs at 9600, 38400 or 115200 baud, not " + std::to_string(config_.baud));
  for (Channel& c : channels_) c.servo = ServoModel(config_.servo, config_.initial_position_us);
  line_.reserve(kMaxLine);
}

double SimSsc32::wire_time(std::size_t bytes) const { return firmware_iface::wire_seconds(bytes, config_.baud); }

bool SimSsc32::moving() const {
  return std::any_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.output > 0 && c.elapsed < c.duration; });
}

void SimSsc32::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  for (std::uint8_t b : bytes) {
    if (b == ssc::kEsc) {
      line_.clear();
      overflow_ = false;
    } else if (b == ssc::kCr) {
      if (!overflow_) execute();
      line_.clear();
      overflow_ = false;
    } else if (line_.size() < kMaxLine) {
      line_.push_back(b);
    } else {
      overflow_ = true;
    }
  }
}

void SimSsc32::execute() {
  ssc::Command c;
  if (ssc::parse_line(line_, &c) != ssc::ParseResult::ok) return;
  if (config_.log_limit) {
    log_.emplace_back(line_.begin(), line_.end());
    if (log_.size() > config_.log_limit) log_.pop_front();
  }
  switch (c.kind) {
    case ssc::Command::Kind::move: return move(c);
    case ssc::Command::Kind::offset:
      for (std::size_t i = 0; i < c.servo_count; ++i) channels_[c.servos[i].channel].offset = c.offsets[i];
      return;
    case ssc::Command::Kind::output:
      for (std::size_t i = 0; i < c.servo_count; ++i) {
        Channel& ch = channels_[c.servos[i].channel];
        ch.output = ch.target = 0;
        ch.elapsed = ch.duration = 0;
      }
      return;
    case ssc::Command::Kind::query_pulse:
      for (std::size_t i = 0; i < c.query_count; ++i) replies_.push_back(ssc::reply_from_pulse(channels_[c.query[i]].output));
      return;
    case ssc::Command::Kind::query_movement:
      replies_.push_back(moving() ? ssc::kMoveInProgress : ssc::kMoveDone);
      return;
  }
}

void SimSsc32::move(const ssc::Command& c) {
  // The group takes the longest of T and every servo's distance at its own speed.
  double duration = c.time_ms / 1000.0;
  for (std::size_t i = 0; i < c.servo_count; ++i) {
    const ssc::ServoMove& m = c.servos[i];
    const Channel& ch = channels_[m.channel];
    if (ch.output > 0 && m.speed_us_per_s > 0) duration = std::max(duration, std::abs(m.pulse_us - ch.output) / m.speed_us_per_s);
  }
  for (std::size_t i = 0; i < c.servo_count; ++i) {
    Channel& ch = channels_[c.servos[i].channel];
    const double first = ch.output > 0 ? ch.output : c.servos[i].pulse_us;  // a first move jumps
    ch.start = ch.output = first;
    ch.target = c.servos[i].pulse_us;
    ch.elapsed = 0;
    ch.duration = duration;  // 0 without S or T: the servo jumps
    if (ch.duration <= 0) ch.output = ch.target;
  }
}

std::size_t SimSsc32::take_replies(std::span<std::uint8_t> out) {
  return take_from(replies_, out);
}

void SimSsc32::advance(double dt_s) {
  if (!(dt_s > 0)) return;
  const int steps = static_cast<int>(std::ceil(dt_s / 0.001));
  const double h = dt_s / steps;
  for (Channel& ch : channels_) {
    for (int i = 0; i < steps; ++i) {
      if (ch.output > 0 && ch.elapsed < ch.duration) {
        ch.elapsed += h;
        if (ch.elapsed > ch.duration - 1e-9) ch.elapsed = ch.duration;  // no rounding left-overs
        ch.output = ch.start + (ch.target - ch.start) * (ch.elapsed / ch.duration);
      }
      ch.servo.step(h, ch.output > 0 ? ch.output + ch.offset : 0);
    }
  }
}

}  // namespace avar::sim
