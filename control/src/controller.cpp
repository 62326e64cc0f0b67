#include "avar/control/controller.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::control {
namespace {

std::vector<std::size_t> bind_tracks(const Rig& rig, const playback::Show& show) {
  std::vector<std::size_t> binding;
  binding.reserve(show.tracks.size());
  for (const playback::Track& track : show.tracks) {
    const auto channel = rig.find_channel(track.channel);
    if (!channel) throw std::invalid_argument("show track '" + track.channel + "' has no channel in the rig");
    binding.push_back(*channel);
  }
  return binding;
}

std::vector<ChannelLimits> limits_of(const Rig& rig) {
  std::vector<ChannelLimits> limits;
  limits.reserve(rig.channels.size());
  for (const ChannelSpec& c : rig.channels)
    limits.push_back({c.min, c.max, c.max_velocity, c.max_acceleration, c.max_jerk, c.soft_margin});
  return limits;
}

}  // namespace

const char* to_string(Phase p) noexcept {
  switch (p) {
    case Phase::idle: return "idle";
    case Phase::homing: return "homing";
    case Phase::running: return "running";
    case Phase::stopping: return "stopping";
    case Phase::finished: return "finished";
  }
  return "unknown";
}

const char* to_string(Stage s) noexcept {
  switch (s) {
    case Stage::sample: return "sample";
    case Stage::limit: return "limit";
    case Stage::send: return "send";
  }
  return "unknown";
}

std::int64_t monotonic_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

void Controller::lap(Stage s, std::int64_t& mark) noexcept {
  if (!options_.stage_clock) return;
  const std::int64_t now = options_.stage_clock();
  StageTime& t = stage_times_[static_cast<std::size_t>(s)];
  t.last_ns = now - mark;
  t.worst_ns = std::max(t.worst_ns, t.last_ns);
  mark = now;
}

const char* to_string(FaultCause c) noexcept {
  switch (c) {
    case FaultCause::none: return "none";
    case FaultCause::non_finite_command: return "non-finite command";
    case FaultCause::link_failure: return "link failure";
  }
  return "unknown";
}

Controller::Controller(const Rig& rig, const playback::Show& show, std::vector<firmware_iface::ActuatorLink*> links,
                       ControllerOptions options)
    : rig_(rig),
      show_(show),
      links_(std::move(links)),
      options_(options),
      sampler_(show, bind_tracks(rig, show), rig.rest_frame()),
      limiter_(limits_of(rig), options.tick_period_s),
      ramp_(rig.channels.size()),
      rest_(rig.rest_frame()),
      ramp_velocity_(rig.channels.size()),
      first_frame_(rig.channels.size()),
      target_(rig.channels.size()),
      commanded_(rig.channels.size()),
      heading_(rig.channels.size()),
      link_dead_(links_.size(), 0) {
  for (std::size_t i = 0; i < rig.channels.size(); ++i) ramp_velocity_[i] = rig.channels[i].ramp_velocity;
  sampler_.sample(0.0, first_frame_);
}

void Controller::begin(double now_s, std::span<const double> start_pose) noexcept {
  limiter_.reset(start_pose);
  const auto from = limiter_.last();
  std::copy(from.begin(), from.end(), commanded_.begin());
  ramp_.plan(commanded_, first_frame_, ramp_velocity_, options_.min_ramp_s);
  phase_ = Phase::homing;
  phase_start_ = now_s;
}

bool Controller::show_over(double show_time_s) const noexcept {
  if (!show_.loop) return show_time_s >= show_.duration;
  return options_.loops > 0 && show_time_s >= static_cast<double>(options_.loops) * show_.duration;
}

void Controller::start_stopping(double now_s) noexcept {
  // From where the limiter is heading (its commands follow that with a fixed delay).
  for (std::size_t i = 0; i < heading_.size(); ++i) heading_[i] = limiter_.heading(i);
  ramp_.plan(heading_, rest_, ramp_velocity_, options_.min_ramp_s);
  phase_ = Phase::stopping;
  phase_start_ = now_s;
}

void Controller::request_stop(double now_s) noexcept {
  stop_requested_ = true;
  if (phase_ == Phase::homing || phase_ == Phase::running) start_stopping(now_s);
}

void Controller::release_now() noexcept {
  for (firmware_iface::ActuatorLink* link : links_) (void)link->release();
  phase_ = Phase::finished;
}

Status Controller::tick(double now_s) noexcept {
  std::int64_t mark = options_.stage_clock ? options_.stage_clock() : 0;
  if (phase_ == Phase::homing) {
    const double t = now_s - phase_start_;
    if (t >= ramp_.duration()) {
      phase_ = Phase::running;
      show_start_ = now_s;
    } else {
      ramp_.sample(t, target_);
    }
  }
  if (phase_ == Phase::running) {
    show_time_ = now_s - show_start_;
    if (show_over(show_time_)) {
      start_stopping(now_s);
    } else {
      sampler_.sample(show_time_, target_);
    }
  }
  if (phase_ == Phase::stopping) ramp_.sample(now_s - phase_start_, target_);
  if (phase_ == Phase::idle || phase_ == Phase::finished) return Status::ok;
  lap(Stage::sample, mark);

  if (limiter_.apply(target_, commanded_) != Status::ok && fault_.cause == FaultCause::none) {
    // The limiter held the offending channels at their last value; ease everything to rest.
    fault_ = {FaultCause::non_finite_command, Status::not_finite, 0, now_s};
    for (std::size_t i = 0; i < target_.size(); ++i)
      if (!std::isfinite(target_[i])) {
        fault_.index = i;
        break;
      }
    if (phase_ != Phase::stopping) start_stopping(now_s);
  }

  lap(Stage::limit, mark);

  Status result = Status::ok;
  bool any_alive = false;
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (link_dead_[i]) continue;
    const Status s = links_[i]->send(commanded_);
    if (s == Status::ok) {
      any_alive = true;
      continue;
    }
    // Nothing more can be sent over this link: its actuators keep their last command (or
    // their own fail-safe). The other links ease to rest.
    link_dead_[i] = 1;
    result = s;
    if (fault_.cause == FaultCause::none) fault_ = {FaultCause::link_failure, s, i, now_s};
    if (phase_ != Phase::stopping) start_stopping(now_s);
  }
  lap(Stage::send, mark);
  if (!any_alive) {
    phase_ = Phase::finished;
    return result;
  }
  if (phase_ == Phase::stopping && now_s - phase_start_ >= ramp_.duration() && limiter_.settled()) phase_ = Phase::finished;
  return result;
}

}  // namespace avar::control
