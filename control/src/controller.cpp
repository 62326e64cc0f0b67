#include "avar/control/controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace avar::control {
namespace {

/// The frame's channel names, by which the sampler binds every track, clip and mask of the show.
std::vector<std::string> channel_names_of(const rig::Rig& rig) {
  std::vector<std::string> names;
  names.reserve(rig.channels.size());
  for (const rig::ChannelSpec& c : rig.channels) names.push_back(c.name);
  return names;
}

std::vector<ChannelLimits> limits_of(const rig::Rig& rig) {
  std::vector<ChannelLimits> limits;
  limits.reserve(rig.channels.size());
  for (const rig::ChannelSpec& c : rig.channels)
    limits.push_back({c.min, c.max, c.max_velocity, c.max_acceleration, c.max_jerk, c.soft_margin, c.digital()});
  return limits;
}

/// Channels that switch rather than move: the soft stop and the fail-safe switch them at once.
std::vector<char> switched_channels(const rig::Rig& rig) {
  std::vector<char> at_once;
  for (const rig::ChannelSpec& c : rig.channels) at_once.push_back(c.digital() ? 1 : 0);
  return at_once;
}

}  // namespace

const char* to_string(Stage s) noexcept {
  switch (s) {
    case Stage::sample: return "sample";
    case Stage::ik: return "ik";
    case Stage::mix: return "mix";
    case Stage::limit: return "limit";
    case Stage::send: return "send";
  }
  return "unknown";
}

ShowBinding::ShowBinding(const rig::Rig& rig, const playback::Show& show_to_bind, std::span<const double> rest_frame,
                         std::shared_ptr<const playback::Show> keep_alive)
    : keep(std::move(keep_alive)), show(&show_to_bind), sampler(show_to_bind, channel_names_of(rig), rest_frame) {
  if (!show_to_bind.targets.empty()) {
    if (!rig.kinematics) throw std::invalid_argument("the show has targets but the rig has no kinematics section");
    ik.emplace(*rig.kinematics, show_to_bind, rest_frame);
  }
}

Controller::Controller(const rig::Rig& rig, const playback::Show& show, std::vector<firmware_iface::ActuatorLink*> links,
                       ControllerOptions options)
    : rig_(rig),
      links_(std::move(links)),
      options_(options),
      rest_(rig.rest_frame()),
      binding_(std::make_unique<ShowBinding>(rig, show, rest_)),
      limiter_(limits_of(rig), options.tick_period_s),
      ramp_(rig.channels.size(), switched_channels(rig)),
      supervisor_(rig, links_.size()),
      failsafe_goal_(rig.channels.size()),
      ramp_velocity_(rig.channels.size()),
      first_frame_(rig.channels.size()),
      target_(rig.channels.size()),
      commanded_(rig.channels.size()),
      heading_(rig.channels.size()),
      measured_(rig.channels.size()),
      measured_known_(rig.channels.size(), 0),
      feedback_(rig.channels.size(), std::numeric_limits<double>::quiet_NaN()),
      telemetry_seen_(rig.channels.size(), 0),
      telemetry_(rig.channels.size()),
      link_telemetry_seen_(rig.channels.size(), 0),
      source_known_(new bool[rig.channels.size()]()) {
  for (std::size_t i = 0; i < rig.channels.size(); ++i) ramp_velocity_[i] = rig.channels[i].ramp_velocity;
  // Each channel's command delay: the longest of the links driving it, in whole ticks.
  delay_ticks_.assign(rig.channels.size(), 0);
  for (const rig::ActuatorSpec& a : rig.actuators) {
    if (a.link.value >= links_.size() || !links_[a.link.value] || !(options_.tick_period_s > 0)) continue;
    const double ticks = std::round(links_[a.link.value]->command_delay_s() / options_.tick_period_s);
    if (ticks > 0 && ticks < 1e6)
      delay_ticks_[a.channel.value] = std::max(delay_ticks_[a.channel.value], static_cast<std::size_t>(ticks));
  }
  for (std::size_t d : delay_ticks_) history_depth_ = std::max(history_depth_, d + 1);
  history_.assign(history_depth_ * rig.channels.size(), 0.0);
  reference_.assign(rig.channels.size(), 0.0);
  sample_show(0.0, first_frame_);
}

void Controller::remember_commands() noexcept {
  const std::size_t n = commanded_.size();
  history_head_ = (history_head_ + 1) % history_depth_;
  std::copy(commanded_.begin(), commanded_.end(), history_.begin() + static_cast<std::ptrdiff_t>(history_head_ * n));
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t frame = (history_head_ + history_depth_ - delay_ticks_[c]) % history_depth_;
    reference_[c] = history_[frame * n + c];
  }
}

std::unique_ptr<ShowBinding> Controller::bind_show(std::shared_ptr<const playback::Show> show) const {
  if (!show) throw std::invalid_argument("no show to bind");
  const playback::Show& s = *show;
  return std::make_unique<ShowBinding>(rig_, s, rest_, std::move(show));
}

void Controller::swap_show(std::unique_ptr<ShowBinding>& next) noexcept {
  if (!next) return;
  binding_.swap(next);
  if (binding_->ik) binding_->ik->reseed(limiter_.last());
}

void Controller::sample_show(double show_time_s, std::span<double> frame) noexcept {
  binding_->sampler.sample(show_time_s, frame);
  // The stage keeps its own tally of converged, degraded and failed solves (IkStage::stats).
  if (binding_->ik) (void)binding_->ik->apply(show_time_s, frame);
}

void Controller::lap(Stage s, std::int64_t& mark) noexcept {
  if (!options_.stage_clock) return;
  const std::int64_t now = options_.stage_clock();
  StageTime& t = stage_times_[static_cast<std::size_t>(s)];
  t.last_ns = now - mark;
  t.worst_ns = std::max(t.worst_ns, t.last_ns);
  mark = now;
}

void Controller::begin(double now_s, std::span<const double> start_pose) noexcept {
  if (supervisor_.phase() != Phase::disabled) return;
  limiter_.reset(start_pose);
  if (binding_->ik) {
    // Solve the first frame from where the figure is, so that homing heads for the solution
    // nearest to it.
    binding_->ik->reseed(limiter_.last());
    sample_show(0.0, first_frame_);
  }
  const auto from = limiter_.last();
  std::copy(from.begin(), from.end(), commanded_.begin());
  // Before the first command, every link's device stands where the figure starts.
  for (std::size_t f = 0; f < history_depth_; ++f) remember_commands();
  // The soft start is the limiter's own glide to the first frame: every channel plans it once
  // and follows it toward the held goal, and the show starts from rest on that frame. The first
  // tick then finds the limiter in cache.
  homing_duration_ = limiter_.glide_duration(first_frame_, ramp_velocity_, options_.min_ramp_s);
  limiter_.glide_to(first_frame_, homing_duration_);
  limiter_.warm(first_frame_);
  supervisor_.enter(Phase::homing);
  phase_start_ = now_s;
  last_now_ = now_s;
  begun_ = true;
  stop_requested_ = false;
  show_start_ = -1;
  show_time_ = 0;
}

double Controller::show_end() const noexcept {
  const playback::Show& show = *binding_->show;
  if (!show.loop) return show.duration;
  return options_.loops > 0 ? static_cast<double>(options_.loops) * show.duration : std::numeric_limits<double>::infinity();
}

bool Controller::show_over(double show_time_s) const noexcept { return show_time_s >= show_end() + options_.lead_out_s; }

void Controller::ease_to(std::span<const double> goal, double now_s) noexcept {
  // From where the limiter is heading (its goal: the commands reach it on a limited profile).
  for (std::size_t i = 0; i < heading_.size(); ++i) heading_[i] = limiter_.heading(i);
  ramp_.plan(heading_, goal, ramp_velocity_, options_.min_ramp_s);
  phase_start_ = now_s;
}

bool Controller::ramp_done(double now_s) const noexcept { return now_s - phase_start_ >= ramp_.duration() && limiter_.settled(); }

void Controller::request_stop(double now_s) noexcept {
  stop_requested_ = true;
  if (supervisor_.phase() != Phase::homing && supervisor_.phase() != Phase::running) return;
  ease_to(rest_, now_s);
  supervisor_.enter(Phase::stopping);
}

void Controller::fault(FaultCause cause, std::size_t index, double value, double now_s, Status status) noexcept {
  if (!supervisor_.latch(cause, index, value, now_s, status)) return;
  supervisor_.release_failsafe(links_);
  for (std::size_t c = 0; c < heading_.size(); ++c) heading_[c] = limiter_.heading(c);
  supervisor_.failsafe_goal(rest_, heading_, failsafe_goal_);
  ease_to(failsafe_goal_, now_s);
}

void Controller::feed_back(std::span<const double> measured, std::span<const bool> known) noexcept {
  for (std::size_t c = 0; c < measured_.size(); ++c) {
    measured_known_[c] = known[c] ? 1 : 0;
    if (known[c]) measured_[c] = measured[c];
  }
}

void Controller::feed_telemetry(std::span<const firmware_iface::ChannelTelemetry> telemetry) noexcept {
  take_telemetry(telemetry, telemetry_seen_, true);
}

void Controller::take_telemetry(std::span<const firmware_iface::ChannelTelemetry> telemetry, std::vector<std::uint64_t>& seen,
                                bool latch) noexcept {
  for (std::size_t c = 0; c < seen.size() && c < telemetry.size(); ++c) {
    const firmware_iface::ChannelTelemetry& t = telemetry[c];
    // A device that stopped answering sends nothing fresh: its silence is judged on every tick.
    if (latch && (t.faults & firmware_iface::kDeviceLost)) fault(FaultCause::device_lost, c, 0, last_now_);
    if (t.updates == seen[c]) continue;
    seen[c] = t.updates;
    if (std::isfinite(t.position)) {
      measured_[c] = t.position;
      measured_known_[c] = 1;
    }
    if (!latch) continue;
    if (t.faults & firmware_iface::kDeviceOverheat) fault(FaultCause::device_overheat, c, t.temperature_c, last_now_);
    if (t.faults & firmware_iface::kDeviceOverload) fault(FaultCause::device_overload, c, t.load, last_now_);
    if (t.faults &
        ~std::uint32_t{firmware_iface::kDeviceOverheat | firmware_iface::kDeviceOverload | firmware_iface::kDeviceLost})
      fault(FaultCause::device_error, c, static_cast<double>(t.faults), last_now_);
  }
}

void Controller::read_feedback(bool latch) noexcept {
  // The devices' reports first, then the position source over them: where both know a channel,
  // the source (the simulator's ground truth, an encoder on the joint) has the last word, as it
  // has over feed_telemetry()'s reports made between ticks.
  for (firmware_iface::ActuatorLink* link : links_) link->read_telemetry(telemetry_);
  take_telemetry(telemetry_, link_telemetry_seen_, latch);
  if (options_.positions) {
    // The source writes straight into measured_, and only where it knows.
    const std::span<bool> known(source_known_.get(), measured_.size());
    std::fill(known.begin(), known.end(), false);
    options_.positions->measure(measured_, known);
    for (std::size_t c = 0; c < known.size(); ++c)
      if (known[c]) measured_known_[c] = 1;
  }
}

void Controller::publish_feedback() noexcept {
  for (std::size_t c = 0; c < feedback_.size(); ++c)
    feedback_[c] = measured_known_[c] ? measured_[c] : std::numeric_limits<double>::quiet_NaN();
}

void Controller::read_final_feedback() noexcept {
  read_feedback(false);
  publish_feedback();
}

bool Controller::active() const noexcept {
  switch (supervisor_.phase()) {
    case Phase::homing:
    case Phase::running:
    case Phase::stopping: return true;
    case Phase::faulted: return supervisor_.driving_failsafe() && supervisor_.any_link_alive() && !ramp_done(last_now_);
    case Phase::disabled: return false;
  }
  return false;
}

bool Controller::reset() noexcept {
  if (supervisor_.phase() != Phase::faulted || active()) return false;
  return supervisor_.clear();
}

void Controller::release_now() noexcept {
  for (firmware_iface::ActuatorLink* link : links_) (void)link->release();
  supervisor_.enter(Phase::disabled);
}

void Controller::tick(double now_s) noexcept {
  std::int64_t mark = options_.stage_clock ? options_.stage_clock() : 0;
  // Before the clock moves on: what the devices reported came with the last tick's exchange.
  read_feedback(true);
  publish_feedback();
  last_now_ = now_s;
  if (!supervisor_.drives()) return;

  // Feedback from the last tick against the command it answered.
  for (std::size_t c = 0; c < measured_known_.size(); ++c) {
    if (!measured_known_[c]) continue;
    measured_known_[c] = 0;
    const double tolerance = rig_.channels[c].tracking_tolerance;
    const double error = std::abs(reference_[c] - measured_[c]);
    if (tolerance > 0 && error > tolerance) fault(FaultCause::tracking_error, c, error, now_s);
  }

  bool sampled_show = false;
  switch (supervisor_.phase()) {
    case Phase::homing:
      if (now_s - phase_start_ >= homing_duration_ && limiter_.settled()) {
        supervisor_.enter(Phase::running);
        show_start_ = now_s;
      } else {
        std::copy(first_frame_.begin(), first_frame_.end(), target_.begin());
        binding_->sampler.warm();  // the show's first samples then find their curves in cache
        break;
      }
      [[fallthrough]];
    case Phase::running: {
      bool clock_stop = false;
      if (options_.show_clock) {
        const ShowClockReading clock = options_.show_clock->read(now_s);
        show_time_ = clock.show_time_s;
        clock_stop = clock.stop;
      } else {
        show_time_ = now_s - show_start_ - options_.lead_in_s;
      }
      if (!clock_stop && !show_over(show_time_)) {
        // The lead-in holds the first frame and the lead-out the last (a looping show's too).
        binding_->sampler.sample(std::clamp(show_time_, 0.0, show_end()), target_);
        sampled_show = true;
        break;
      }
      ease_to(rest_, now_s);
      supervisor_.enter(Phase::stopping);
    }
      [[fallthrough]];
    case Phase::stopping:
    case Phase::faulted: ramp_.sample(now_s - phase_start_, target_); break;
    case Phase::disabled: break;
  }
  lap(Stage::sample, mark);
  if (sampled_show && binding_->ik)
    (void)binding_->ik->apply(std::clamp(show_time_, 0.0, show_end()), target_, options_.aims, options_.live,
                              now_s);  // tallied in IkStage::stats
  lap(Stage::ik, mark);
  if (sampled_show && options_.live) options_.live->apply(now_s, target_);
  lap(Stage::mix, mark);

  if (limiter_.apply(target_, commanded_) != Status::ok) {
    std::size_t bad = 0;
    while (bad + 1 < target_.size() && std::isfinite(target_[bad])) ++bad;
    fault(FaultCause::non_finite, bad, 0, now_s, Status::not_finite);
  }
  remember_commands();
  lap(Stage::limit, mark);

  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (supervisor_.link_dead(i)) continue;
    const Status s = links_[i]->send(commanded_);
    if (s == Status::ok) continue;
    // Nothing more can be sent over this link: its actuators keep their last command (or the
    // device's own fail-safe). The other links do their fail-safe actions.
    supervisor_.link_died(i);
    fault(s == Status::timeout ? FaultCause::link_watchdog : FaultCause::link_failure, i, 0, now_s, s);
  }
  lap(Stage::send, mark);

  if (supervisor_.phase() == Phase::stopping && ramp_done(now_s)) supervisor_.enter(Phase::disabled);
}

}  // namespace avar::control
