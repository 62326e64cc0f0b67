#include "avar/session/figure_run.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <thread>

#include "avar/assembly/digital_inputs.hpp"

namespace avar::session {
namespace {

std::unique_ptr<IdleSession> open_idle(const rig::Rig& rig, const playback::Show& show, const FigureRunSetup& setup) {
  if (!setup.idle_seed) return nullptr;
  return std::make_unique<IdleSession>(rig, show, *setup.idle_seed);
}

std::unique_ptr<LiveSession> open_live(const rig::Rig& rig, const config::InputMap& map, const FigureRunSetup& setup) {
  // Digital inputs of the rig with the control role feed the mappings too.
  const bool gpio_controls = !map.mappings.empty() && has_control_inputs(rig);
  if (setup.input_uris.empty() && !gpio_controls) return nullptr;
  return std::make_unique<LiveSession>(rig, map, setup.input_uris);
}

std::unique_ptr<TimecodeRun> open_chase(const FigureRunSetup& setup) {
  const ShowControlOptions& control = setup.show_control;
  if (!control.source) return nullptr;
  if (control.osc_control) throw std::invalid_argument("--osc-control and --timecode both drive show time; give one");
  // Ten minutes of trace columns reserved; longer runs grow as they go.
  auto chase =
      std::make_unique<TimecodeRun>(control, setup.session.stepped, static_cast<std::size_t>(600 * setup.session.rate_hz));
  chase->start();
  return chase;
}

std::unique_ptr<OscControlSurface> open_surface(const playback::Show& show, const FigureRunSetup& setup) {
  if (!setup.show_control.osc_control) return nullptr;
  auto surface = std::make_unique<OscControlSurface>(*setup.show_control.osc_control, show.name);
  surface->start();
  return surface;
}

}  // namespace

playback::Show live_only_show(std::optional<double> duration_s) {
  playback::Show show;
  show.name = "live";
  show.duration = duration_s.value_or(std::numeric_limits<double>::infinity());
  return show;
}

bool has_control_inputs(const rig::Rig& rig) {
  return std::any_of(rig.digital_inputs.begin(), rig.digital_inputs.end(),
                     [](const rig::DigitalInputSpec& d) { return d.role == rig::InputRole::control; });
}

FigureRun::FigureRun(const rig::Rig& rig, const playback::Show& show, const config::InputMap& map, FigureRunSetup setup)
    : rig_(rig), cues_(show) {
  // Each part opens before anything moves, in this order: a file's mistake in the idle section
  // first, then the devices and sockets; a failure unwinds what was opened.
  idle_ = open_idle(rig, show, setup);
  live_ = open_live(rig, map, setup);
  chase_ = open_chase(setup);
  surface_ = open_surface(show, setup);

  SessionConfig config = std::move(setup.session);
  // GPIO chips are shared by the gpio links and the digital inputs (the e-stop).
  if (!config.links.gpio_chips) config.links.gpio_chips = std::make_shared<assembly::GpioChips>(config.links.simulate_all);
  gpio_chips_ = config.links.gpio_chips;
  config.live = nullptr;
  config.recorded_controls = nullptr;
  config.external_clock = nullptr;
  if (live_) config.live = &live_->inputs(), config.recorded_controls = &live_->inputs();
  if (idle_) config.live = idle_->layers(config.live);
  if (chase_) config.external_clock = &chase_->clock();
  if (surface_) config.external_clock = surface_.get();
  session_ = std::make_unique<ShowSession>(rig, show, std::move(config));
  digital_inputs_ = assembly::open_digital_inputs(rig, *gpio_chips_);
}

// Members go in reverse order: the digital inputs (which post into the live inputs) first, the
// live inputs last.
FigureRun::~FigureRun() = default;

void FigureRun::watch_inputs() {
  if (!digital_inputs_) return;
  if (live_) digital_inputs_->start(live_->inputs().sink());
  else digital_inputs_->start();
}

std::string FigureRun::start_button_names() const {
  std::string names;
  for (const rig::DigitalInputSpec& d : rig_.digital_inputs)
    if (d.role == rig::InputRole::start) names += (names.empty() ? "'" : ", '") + d.name + "'";
  return names;
}

StartWait FigureRun::wait_for_start_button(const std::atomic<int>& interrupts) const {
  if (!digital_inputs_ || start_button_names().empty()) return StartWait::no_button;
  while (digital_inputs_->start_presses() == 0) {
    if (interrupts.load() > 0) return StartWait::interrupted;
    if (digital_inputs_->estop().load()) return StartWait::estop;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return StartWait::pressed;
}

std::optional<LinkProblem> FigureRun::start() {
  if (std::optional<LinkProblem> problem = session_->start_links()) return problem;
  session_->begin();
  if (idle_) idle_->watch(session_->controller());
  return std::nullopt;
}

control::RunResult FigureRun::run(const std::atomic<int>& interrupts, const std::atomic<bool>* keyboard_estop) {
  if (keyboard_estop) session_->add_estop_input(*keyboard_estop);
  if (digital_inputs_) session_->add_estop_input(digital_inputs_->estop());
  // The loop's own observer: the cues fire by show time, behind the show-time source's watch.
  control::TickObserver* observer = &cues_;
  if (chase_) chase_->forward_to(cues_), observer = chase_.get();
  if (surface_) {
    surface_->forward_to(cues_), observer = surface_.get();
    session_->add_estop_input(surface_->estop());
  }
  session_->set_loop_observer(observer);
  control::RunResult result = session_->run(interrupts);
  cues_.flush();
  if (chase_) chase_->stop();
  if (surface_) surface_->stop();
  if (live_) live_->stop();
  return result;
}

std::size_t FigureRun::recorded_controls() const noexcept { return live_ ? live_->inputs().control_values().size() : 0; }

}  // namespace avar::session
