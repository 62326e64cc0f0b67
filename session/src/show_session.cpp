#include "avar/session/show_session.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include "avar/core/input_error.hpp"

namespace avar::session {
namespace {

assembly::LinkSelection selection_for(const SessionConfig& config) {
  if (!(config.rate_hz >= 1 && config.rate_hz <= 1000))
    throw std::invalid_argument("a session's rate must be 1 to 1000 ticks per second");
  assembly::LinkSelection links = config.links;
  // Stepped time sends on the loop thread (deterministic); real time gives each link its own
  // I/O thread and watchdog.
  links.threaded_rate_hz = config.stepped ? 0.0 : config.rate_hz;
  return links;
}

bool show_time_command(CommandKind kind) {
  return kind == CommandKind::play || kind == CommandKind::pause || kind == CommandKind::seek || kind == CommandKind::scrub ||
         kind == CommandKind::loop;
}

}  // namespace

ShowSession::ShowSession(const rig::Rig& rig, const playback::Show& show, SessionConfig config)
    : rig_(rig),
      show_(&show),
      config_(std::move(config)),
      figure_(std::make_unique<assembly::FigureLinks>(rig, selection_for(config_))),
      links_(figure_->links()),
      clock_(config_.lead_in_s, config_.external_clock, config_.start_paused, config_.hold_at_end),
      holds_(rig, config_.live),
      queue_(config_.command_capacity),
      ring_(config_.record_capacity, rig.channels.size(), rig.links.size(),
            config_.recorded_controls ? config_.recorded_controls->control_values().size() : 0) {
  if (config_.stepped && !figure_->all_simulated()) throw NeedsSimulatedLinks();
}

NeedsSimulatedLinks::NeedsSimulatedLinks()
    : std::invalid_argument("a stepped session runs on a simulated clock and needs every link simulated") {}

ShowSession::~ShowSession() { free_handover(); }

void ShowSession::free_handover() noexcept {
  delete pending_show_.exchange(nullptr);
  delete retired_show_;
  retired_show_ = nullptr;
}

bool ShowSession::replace_show(std::shared_ptr<const playback::Show> show, std::chrono::milliseconds wait) {
  const std::lock_guard<std::mutex> lock(replace_mutex_);
  if (!controller_) return false;
  std::unique_ptr<control::ShowBinding> next = controller_->bind_show(std::move(show));
  // The show handed over before must have been taken first.
  const auto deadline = std::chrono::steady_clock::now() + wait;
  while (pending_show_.load(std::memory_order_acquire) != nullptr) {
    if (!running_.load() || std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  if (!running_.load()) return false;
  delete retired_show_;
  retired_show_ = nullptr;
  pending_show_.store(next.release(), std::memory_order_release);
  return true;
}

void ShowSession::add_estop_input(const std::atomic<bool>& pressed) {
  for (const std::atomic<bool>*& slot : estop_inputs_)
    if (!slot) {
      slot = &pressed;
      return;
    }
  throw std::length_error("a session watches at most three e-stop inputs beside its own");
}

bool ShowSession::command(const Command& c) noexcept {
  if (queue_.push(c)) return true;
  commands_dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

std::optional<LinkProblem> ShowSession::start_links() {
  for (std::size_t i = 0; i < links_.size(); ++i)
    if (const Status s = links_[i]->start(); s != Status::ok) return LinkProblem{i, s, links_[i]->start_problem()};
  return std::nullopt;
}

void ShowSession::begin() {
  if (running_.load()) throw std::logic_error("begin() while a run is under way");
  // Start pose: what the devices report, the rest pose for the rest.
  std::vector<double> start_pose = rig_.rest_frame();
  std::unique_ptr<bool[]> known(new bool[rig_.channels.size()]());
  for (firmware_iface::ActuatorLink* link : links_)
    (void)link->read_positions(start_pose, std::span<bool>(known.get(), rig_.channels.size()));

  free_handover();
  control::ControllerOptions options;
  options.tick_period_s = 1.0 / config_.rate_hz;
  // On the simulated clock a run is deterministic, trace included: stages are not timed.
  if (config_.stepped) options.stage_clock = nullptr;
  if (show_->loop) options.loops = config_.loops;
  options.positions = figure_.get();  // the simulator's ground truth, for simulated links
  options.live = &holds_;
  options.aims = &aims_;
  options.lead_in_s = config_.lead_in_s;
  options.lead_out_s = config_.hold_at_end ? std::numeric_limits<double>::infinity() : config_.lead_out_s;
  options.show_clock = &clock_;
  controller_ = std::make_unique<control::Controller>(rig_, *show_, links_, options);
  clock_.attach(*controller_);
  controller_->begin(0.0, start_pose);
}

control::RunResult ShowSession::run(const std::atomic<int>& interrupts) {
  if (!controller_) throw std::logic_error("run() before begin()");
  control::RunOptions options{config_.rate_hz, config_.stepped ? control::ClockMode::stepped : control::ClockMode::realtime,
                              config_.realtime};
  options.deadline_miss_budget = config_.deadline_miss_budget;
  options.estop = estop_inputs_[0];
  options.estop_input = estop_inputs_[1];
  options.estop_remote = estop_inputs_[2];
  options.plant = figure_.get();
  running_.store(true);
  control::RunResult result;
  if (config_.stepped) {
    result = control::run_loop(*controller_, options, *this, interrupts);
  } else {
    std::atomic<bool> done{false};
    std::exception_ptr failure;
    std::thread loop([&] {
      try {
        result = control::run_loop(*controller_, options, *this, interrupts);
      } catch (...) {
        failure = std::current_exception();
      }
      done.store(true, std::memory_order_release);
      ring_.wake();
    });
    // This thread publishes: records to the observers as they come.
    for (;;) {
      const std::uint32_t token = ring_.signal();
      drain();
      if (done.load(std::memory_order_acquire)) break;
      ring_.wait(token);
    }
    loop.join();
    if (failure) {
      running_.store(false);
      std::rethrow_exception(failure);
    }
  }
  drain();
  controller_->read_final_feedback();
  running_.store(false);
  return result;
}

void ShowSession::drain() {
  while (const TickRecord* record = ring_.front()) {
    for (SessionObserver* o : observers_) o->on_tick(*record);
    ring_.pop();
  }
}

CommandOutcome ShowSession::apply(const Command& c, double now_s, control::Controller& controller) noexcept {
  const control::Phase phase = controller.phase();
  const bool live = phase == control::Phase::homing || phase == control::Phase::running;
  if (show_time_command(c.kind)) return live ? clock_.apply(c, now_s) : CommandOutcome::not_running;
  switch (c.kind) {
    case CommandKind::hold:
      if (c.channel >= holds_.channel_count()) return CommandOutcome::bad_channel;
      if (!std::isfinite(c.value)) return CommandOutcome::bad_value;
      (void)holds_.hold(c.channel, c.value);
      return CommandOutcome::applied;
    case CommandKind::release:
      if (c.channel >= holds_.channel_count()) return CommandOutcome::bad_channel;
      holds_.release(c.channel);
      return CommandOutcome::applied;
    case CommandKind::aim:
    case CommandKind::unaim: {
      const control::IkStage* ik = controller.ik();
      if (!ik || c.channel >= ik->goal_count() || c.channel >= control::TargetAims::kCapacity) return CommandOutcome::bad_target;
      if (c.kind == CommandKind::unaim) {
        aims_.release(c.channel);
        return CommandOutcome::applied;
      }
      const Eigen::Vector3d point(c.point[0], c.point[1], c.point[2]);
      return aims_.aim(c.channel, point) ? CommandOutcome::applied : CommandOutcome::bad_value;
    }
    case CommandKind::stop:
      if (!live) return CommandOutcome::not_running;
      controller.request_stop(now_s);
      return CommandOutcome::applied;
    default: return CommandOutcome::bad_value;
  }
}

void ShowSession::before_tick(std::uint64_t, double now_s, control::Controller& controller) noexcept {
  if (estop_.load(std::memory_order_relaxed) && !estop_seen_) {
    estop_seen_ = true;
    controller.fault(control::FaultCause::estop, 0, 0, now_s);
  }
  if (control::ShowBinding* next = pending_show_.load(std::memory_order_acquire)) {
    std::unique_ptr<control::ShowBinding> swap(next);
    controller.swap_show(swap);
    retired_show_ = swap.release();
    pending_show_.store(nullptr, std::memory_order_release);
  }
  taken_count_ = 0;
  Command c;
  while (taken_count_ < kMaxCommandsPerTick && queue_.pop(c)) {
    taken_[taken_count_] = {c, apply(c, now_s, controller)};
    ++taken_count_;
  }
}

void ShowSession::after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) {
  if (loop_observer_) loop_observer_->after_tick(tick, now_s, dt_s, lateness_s, controller);
  if (TickRecord* r = ring_.claim()) {
    r->tick = tick;
    r->now_s = now_s;
    r->lateness_s = lateness_s;
    r->phase = controller.phase();
    r->show_time_s = controller.show_time();
    r->paused = clock_.paused();
    r->looping = clock_.looping();
    r->estop = estop_seen_;
    r->stop_requested = controller.stop_requested();
    r->fault = controller.latched_fault();
    r->faults_seen = controller.faults_seen();
    r->command_count = taken_count_;
    for (std::size_t i = 0; i < taken_count_; ++i) r->commands[i] = taken_[i];
    const control::IkStage* ik = controller.ik();
    r->target_count = ik ? std::min(ik->goal_count(), r->targets.size()) : 0;
    for (std::size_t i = 0; i < r->target_count; ++i) {
      const Eigen::Vector3d& p = ik->goal_position(i);
      r->targets[i] = {{p.x(), p.y(), p.z()}, aims_.held(i)};
    }
    const auto target = controller.target();
    const auto command = controller.commanded();
    const auto reference = controller.tracking_reference();
    const auto measured = controller.measured();
    const auto telemetry = controller.telemetry();
    for (std::size_t c = 0; c < r->channels.size(); ++c) {
      ChannelRecord& ch = r->channels[c];
      ch.target = target[c];
      ch.command = command[c];
      ch.reference = reference[c];
      ch.measured = measured[c];
      ch.temperature_c = telemetry[c].temperature_c;
      ch.load = telemetry[c].load;
      ch.device_faults = telemetry[c].faults;
      ch.held = holds_.held(c);
    }
    for (std::size_t l = 0; l < r->links.size(); ++l) r->links[l] = links_[l]->counters();
    for (std::size_t s = 0; s < control::kStageCount; ++s)
      r->stage_ns[s] = controller.stage_time(static_cast<control::Stage>(s)).last_ns;
    if (config_.recorded_controls) {
      const auto values = config_.recorded_controls->control_values();
      const std::size_t n = std::min(values.size(), r->controls.size());
      std::copy(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n), r->controls.begin());
    }
    ring_.publish();
  }
  taken_count_ = 0;
  // On the stepped clock the caller's thread is the publisher: every record goes out now.
  if (config_.stepped) drain();
}

}  // namespace avar::session
