#pragma once
// A show session: the library's way to run a figure. It owns the figure's links
// (assembly::FigureLinks), the controller and the runner; takes commands from any thread; and
// publishes what happens, tick by tick, to observers.
//
//   ShowSession session(rig, show, config);     // opens the links (real or simulated)
//   session.add_observer(watcher);               // SessionObserver: every TickRecord
//   if (auto problem = session.start_links()) ... // a link that would not start
//   session.begin();                             // the controller, homing from the devices' pose
//   control::RunResult r = session.run(interrupts);  // to the end of the run
//
// Commands (any thread, lock-free, never blocking; false when the queue is full): play, pause,
// seek and scrub (show time jumps; the limiter turns the jump into a glide), loop on/off, hold a
// channel at a value / release it (a layer over the show: clamped to the channel's range, moved
// within its speed and acceleration limits), stop (ease to rest, end the run), and e-stop (a
// flag, never lost to a full queue: the controller faults and every actuator takes its
// fail-safe action). The loop takes queued commands at the start of a tick, at most
// kMaxCommandsPerTick a tick; each tick's record lists them with their outcome.
//
// Threads. In real time the runner ticks on a loop thread of its own (scheduled as
// SessionConfig::realtime asks) and run()'s caller becomes the publisher: it waits for records
// and hands them to the observers. On the stepped clock (every link simulated) the loop runs on
// run()'s caller and each record goes to the observers right after its tick: deterministic,
// nothing lost. The path out of the tick is a preallocated ring of fixed-size records; in real
// time a full ring drops records (records_dropped()). The tick itself allocates nothing.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/assembly/figure_links.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/live_inputs.hpp"
#include "avar/control/runner.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"
#include "avar/session/command_queue.hpp"
#include "avar/session/hold_layer.hpp"
#include "avar/session/session_clock.hpp"
#include "avar/session/tick_record.hpp"

namespace avar::session {

struct SessionConfig {
  double rate_hz = 50;   ///< ticks per second, 1 to 1000
  bool stepped = false;  ///< the simulated clock, on run()'s caller (every link must be simulated)
  /// Which links to open and how (port override, simulate all, GPIO chips, a simulated device's
  /// preparation). threaded_rate_hz is the session's to set: rate_hz in real time, 0 stepped.
  assembly::LinkSelection links;
  /// Passes of a looping show; 0: until stopped.
  std::uint64_t loops = 0;
  double lead_in_s = 0;   ///< ControllerOptions::lead_in_s (idle before the show)
  double lead_out_s = 0;  ///< ControllerOptions::lead_out_s (idle after it)
  /// Layers under the holds (idle life, live inputs; borrowed, loop thread). nullptr: none.
  control::LiveLayer* live = nullptr;
  /// Live inputs whose control values every record carries (TickRecord::controls; borrowed,
  /// read on the loop thread). nullptr: none.
  const control::LiveInputs* recorded_controls = nullptr;
  /// Show time from elsewhere (a timecode chase, a control surface; borrowed, loop thread). The
  /// show-time commands are refused then. nullptr: the session's own clock.
  control::ShowClock* external_clock = nullptr;
  /// Show time stands at the first frame until play.
  bool start_paused = false;
  /// The run does not end with the show (an editor's session): show time stops at the end of a
  /// pass that would end the show, the figure holds that frame (lead_out_s is ignored), and play
  /// there starts the show over; the run ends on stop, Ctrl-C or a fault.
  bool hold_at_end = false;
  control::RealtimeRequest realtime{50, true, -1};  ///< the loop thread's scheduling (real time)
  std::uint64_t deadline_miss_budget = UINT64_MAX;  ///< more misses in a run is a fault
  std::size_t command_capacity = 64;                ///< queued commands
  std::size_t record_capacity = 256;                ///< tick records between the loop and the publisher
};

/// A stepped session (SessionConfig::stepped) asked for with a link that is not simulated.
class NeedsSimulatedLinks : public std::invalid_argument {
 public:
  NeedsSimulatedLinks();
};

/// A link that did not start (start_links()).
struct LinkProblem {
  std::size_t link = 0;
  Status status = Status::ok;
  std::string problem;  ///< the link's own words (ActuatorLink::start_problem), may be empty
};

class ShowSession final : private control::TickObserver {
 public:
  /// Opens the rig's links as config.links selects (InputError naming the port when one cannot
  /// be opened). NeedsSimulatedLinks for a stepped session with a real link; a rate out of
  /// range is std::invalid_argument.
  /// `rig` and `show` are borrowed and must outlive the session.
  ShowSession(const rig::Rig& rig, const playback::Show& show, SessionConfig config);
  ~ShowSession() override;
  ShowSession(const ShowSession&) = delete;
  ShowSession& operator=(const ShowSession&) = delete;

  /// Plays another show from the run's next tick (a show edited while it plays), at the same
  /// show time; the limiter turns the change into a glide. The show must be validated against
  /// the rig; the session shares it until a later show replaces it. Any thread, the loop's
  /// observers included (callers are serialised). Binds the show here, off the loop thread
  /// (std::invalid_argument as Controller's constructor); the loop takes it at its next tick
  /// without allocating. False, and nothing changes, when no run is under way or the show
  /// handed over before is still waiting for a tick after `wait`. The next begin() plays the
  /// show load() gave again.
  bool replace_show(std::shared_ptr<const playback::Show> show, std::chrono::milliseconds wait = std::chrono::milliseconds(1000));
  /// Replaces the show (borrowed) for the next begin(). Only while no run is under way:
  /// std::logic_error otherwise. The show must be validated against the rig already.
  void load(const playback::Show& show);
  /// Adds an observer of the tick records (borrowed). Before run().
  void add_observer(SessionObserver& observer) { observers_.push_back(&observer); }
  /// Watches every tick on the loop thread, before its record is published (a recorder that
  /// reads the links themselves; borrowed, nullptr: none). Before run(); quick in real time.
  void set_loop_observer(control::TickObserver* observer) noexcept { loop_observer_ = observer; }
  /// An e-stop input beside the session's own: the keyboard's, a GPIO input, a remote's
  /// (borrowed, read every tick; at most three). Before run(); std::length_error past three.
  void add_estop_input(const std::atomic<bool>& pressed);

  // Commands: any thread, lock-free. False when the queue is full (the command is dropped).
  bool play() noexcept { return command({CommandKind::play, 0, 0}); }
  bool pause() noexcept { return command({CommandKind::pause, 0, 0}); }
  bool seek(double show_time_s) noexcept { return command({CommandKind::seek, 0, show_time_s}); }
  bool scrub(double show_time_s) noexcept { return command({CommandKind::scrub, 0, show_time_s}); }
  bool loop(bool on) noexcept { return command({CommandKind::loop, 0, on ? 1.0 : 0.0}); }
  bool hold(std::size_t channel, double value) noexcept {
    return command({CommandKind::hold, static_cast<std::uint32_t>(channel), value});
  }
  bool release(std::size_t channel) noexcept { return command({CommandKind::release, static_cast<std::uint32_t>(channel), 0}); }
  bool stop() noexcept { return command({CommandKind::stop, 0, 0}); }
  bool command(const Command& c) noexcept;
  /// E-stop: latched on the next tick whatever the queue holds. Any thread, lock-free.
  void estop() noexcept { estop_.store(true, std::memory_order_relaxed); }

  /// Starts every link; the first that does not start is returned (nothing moved yet).
  std::optional<LinkProblem> start_links();
  /// Builds the controller for the loaded show and begins homing from the pose the devices
  /// report (the rest pose where they report none). Allocates; not while a run is under way.
  void begin();
  /// Runs until the controller is done (the show ended and the figure eased to rest, a stop, or
  /// a fault's fail-safe motions ended). `interrupts`: Ctrl-C count (control::run_loop). After
  /// begin(); returns when every record reached the observers, with controller().measured()
  /// and telemetry() read once more: where the figure stood after the last tick's command.
  control::RunResult run(const std::atomic<int>& interrupts);

  const rig::Rig& rig() const noexcept { return rig_; }
  assembly::FigureLinks& figure() noexcept { return *figure_; }
  const assembly::FigureLinks& figure() const noexcept { return *figure_; }
  /// After begin(). Read the controller from another thread only when no run is under way.
  const control::Controller& controller() const noexcept { return *controller_; }
  double rate_hz() const noexcept { return config_.rate_hz; }
  bool stepped() const noexcept { return config_.stepped; }
  std::uint64_t records_dropped() const noexcept { return ring_.dropped(); }
  std::uint64_t commands_dropped() const noexcept { return commands_dropped_.load(std::memory_order_relaxed); }

 private:
  void before_tick(std::uint64_t tick, double now_s, control::Controller& controller) noexcept override;
  void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) override;
  CommandOutcome apply(const Command& c, double now_s, control::Controller& controller) noexcept;
  /// Hands every published record to the observers (the publisher's side).
  void drain();

  const rig::Rig& rig_;
  const playback::Show* show_;
  SessionConfig config_;
  std::unique_ptr<assembly::FigureLinks> figure_;
  std::vector<firmware_iface::ActuatorLink*> links_;
  SessionClock clock_;
  HoldLayer holds_;
  control::TargetAims aims_;  ///< targets held by aim commands; the loop thread only
  std::unique_ptr<control::Controller> controller_;
  CommandQueue queue_;
  TickRing ring_;
  std::vector<SessionObserver*> observers_;
  control::TickObserver* loop_observer_ = nullptr;
  std::array<const std::atomic<bool>*, 3> estop_inputs_{};
  std::atomic<bool> estop_{false};
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> commands_dropped_{0};
  // Loop thread only: the commands this tick took, for its record.
  std::array<CommandRecord, kMaxCommandsPerTick> taken_{};
  std::size_t taken_count_ = 0;
  bool estop_seen_ = false;
  // The show hand-over (replace_show): the replacing thread stores a binding in pending_show_
  // only when it is null; the loop thread swaps it in, leaves the binding it replaced in
  // retired_show_, then clears pending_show_ (release). The replacing thread frees retired_show_
  // only after it saw pending_show_ null (acquire): each side writes only in its own state.
  std::mutex replace_mutex_;
  std::atomic<control::ShowBinding*> pending_show_{nullptr};
  control::ShowBinding* retired_show_ = nullptr;
  void free_handover() noexcept;
};

}  // namespace avar::session
