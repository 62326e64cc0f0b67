#include "avar/play_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>

#include "avar/config/input_map.hpp"
#include "avar/config/mocap_bake.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/interrupts.hpp"
#include "avar/session/figure_run.hpp"
#include "avar/session/play_recorder.hpp"
#include "avar/session/take.hpp"
#include "avar/svg_plot.hpp"

namespace avar::app {

using config::load_playable_show;
using session::fresh_idle_seed;
using session::IdleSession;
using session::LiveSession;
using session::OscControlSurface;
using session::PhaseMark;
using session::PlayRecorder;
using session::TimecodeRun;
using session::TraceColumn;
namespace {

struct Loaded {
  rig::Rig rig;
  playback::Show show;
  config::InputMap inputs;
};

/// Loads and validates the files whole (rig, show, inputs). Prints every problem; returns
/// nullopt on any error.
std::optional<Loaded> load_and_check(const PlayOptions& o, std::ostream& err) {
  try {
    rig::Rig rig = config::load_rig_file(o.rig_path);
    playback::Show show = o.live_only ? session::live_only_show(o.duration_s) : load_playable_show(o.show_path, o.map_path, rig);
    Loaded loaded{std::move(rig), std::move(show), {}};
    loaded.inputs = o.inputs_path ? config::load_input_map(loaded.rig, *o.inputs_path, true)
                                  : config::load_input_map(loaded.rig, o.rig_path, false);
    if (o.live_only) return loaded;
    const config::ShowCheck check = config::check_show_against_rig(loaded.show, loaded.rig);
    for (const auto& w : check.warnings) err << "warning: " << w.to_string() << '\n';
    for (const auto& e : check.errors) err << "error: " << e.to_string() << '\n';
    if (!check.ok()) return std::nullopt;
    return loaded;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return std::nullopt;
  }
}

void print_summary(std::ostream& out, const Loaded& loaded, const assembly::FigureLinks& figure,
                   const control::Controller& controller, const PlayRecorder& recorder, const control::RunResult& run,
                   bool realtime, double rate_hz, const LiveSession* live) {
  const rig::Rig& rig = loaded.rig;
  out << "\nplayed '" << loaded.show.name << "' on rig '" << rig.name << "' at " << rate_hz << " Hz, "
      << (realtime ? "real time" : "simulated time") << '\n';
  if (live) live->describe(out);
  for (std::size_t i = 0; i < rig.links.size(); ++i) {
    out << "  link " << rig.links[i].name << ": " << figure.describe(i) << '\n';
    // Smart buses answer: report the health of the wire.
    const firmware_iface::LinkCounters k = figure.links()[i]->counters();
    if (k.replies > 0 || k.timeouts > 0 || k.reconnects > 0)
      out << "    " << k.exchanges << " exchanges, " << k.replies << " replies, " << k.crc_errors << " CRC errors, "
          << k.framing_errors << " framing errors, " << k.timeouts << " timeouts, " << k.retries << " retries, "
          << k.device_errors << " device errors, " << k.reconnects << " reconnects\n";
  }
  for (std::size_t i = 0; i < recorder.phases().size(); ++i) {
    const PhaseMark& p = recorder.phases()[i];
    if (p.phase == control::Phase::disabled) continue;
    out << "  " << std::left << std::setw(9) << control::to_string(p.phase) << std::right << "from " << format_fixed(p.time_s, 2)
        << " s\n";
  }
  out << '\n'
      << std::left << std::setw(12) << "channel" << std::setw(6) << "unit" << std::right << std::setw(11) << "max err"
      << std::setw(11) << "rms err" << std::setw(9) << "clamped" << std::setw(10) << "max lag" << '\n';
  for (std::size_t i = 0; i < rig.channels.size(); ++i) {
    const auto& c = rig.channels[i];
    const auto& s = recorder.stats();
    out << std::left << std::setw(12) << c.name << std::setw(6) << c.unit << std::right << std::setw(11)
        << (s.has_samples(i) ? format_fixed(s.max_abs_error(i), 3) : "-") << std::setw(11)
        << (s.has_samples(i) ? format_fixed(s.rms_error(i), 3) : "-") << std::setw(9) << controller.limiter().clamped(i)
        << std::setw(10) << format_fixed(controller.limiter().max_lag(i), 3) << '\n';
  }
  if (!recorder.has_measurements())
    out << "(no position feedback on these links: tracking error needs the simulator or a device that reports positions)\n";
  std::uint64_t saturated = 0;
  for (auto* link : figure.links()) saturated += link->saturated_pulses();
  out << "\nticks " << run.ticks << ", deadline misses " << run.deadline_misses << ", pulses saturated by calibration "
      << saturated << ", bytes sent " << figure.bytes_sent() << '\n';
  if (const control::IkStage* ik = controller.ik()) {
    const control::IkStats& k = ik->stats();
    out << "inverse kinematics: " << k.converged << " solves converged, " << k.degraded
        << " degraded (target out of reach: closest pose used), " << k.failed << " failed; worst residual "
        << format_fixed(k.worst_position_error * 1000.0, 3) << " mm, "
        << format_fixed(k.worst_orientation_error * 180.0 / 3.141592653589793, 3) << "°\n";
  }
  if (realtime) {
    const auto us = [](std::int64_t ns) { return format_fixed(static_cast<double>(ns) / 1000.0, 1); };
    out << "wake-up lateness (µs): p50 " << us(run.lateness.percentile_ns(0.5)) << ", p99 "
        << us(run.lateness.percentile_ns(0.99)) << ", p99.9 " << us(run.lateness.percentile_ns(0.999)) << ", max "
        << us(run.lateness.max_ns()) << "; scheduling: " << (run.realtime.fifo ? "SCHED_FIFO" : "normal")
        << (run.realtime.memory_locked ? ", memory locked" : "") << (run.realtime.pinned ? ", pinned" : "") << '\n';
  }
  if (!realtime) return;
  out << "tick stages (µs, last / worst):";
  for (std::size_t i = 0; i < control::kStageCount; ++i) {
    const auto stage = static_cast<control::Stage>(i);
    const control::StageTime& t = controller.stage_time(stage);
    out << ' ' << control::to_string(stage) << ' ' << format_fixed(static_cast<double>(t.last_ns) / 1000.0, 1) << " / "
        << format_fixed(static_cast<double>(t.worst_ns) / 1000.0, 1) << (i + 1 < control::kStageCount ? "," : "\n");
  }
}

void write_trace(const std::string& path, const rig::Rig& rig, const assembly::FigureLinks& figure, const PlayRecorder& r,
                 const LiveSession* live, const std::vector<TraceColumn>& extra) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write trace file " + path);
  // Channels on smart buses also get what their devices report; smart buses, their wire counters.
  std::vector<char> reported(rig.channels.size(), 0);
  for (const rig::ActuatorSpec& a : rig.actuators)
    if (figure.reports_telemetry(a.link.value)) reported[a.channel.value] = 1;
  std::vector<std::size_t> counted_links;
  for (std::size_t l = 0; l < rig.links.size(); ++l)
    if (figure.reports_telemetry(l)) counted_links.push_back(l);
  csv << "seconds,phase,wake_late_us,sample_us,ik_us,mix_us,limit_us,send_us";
  for (std::size_t i = 0; i < rig.channels.size(); ++i) {
    const std::string& c = rig.channels[i].name;
    csv << ',' << c << ".target," << c << ".command," << c << ".measured";
    if (reported[i]) csv << ',' << c << ".load," << c << ".temperature_c," << c << ".device_faults";
  }
  for (std::size_t l : counted_links) {
    const std::string& name = rig.links[l].name;
    csv << ',' << name << ".replies," << name << ".crc_errors," << name << ".framing_errors," << name << ".timeouts," << name
        << ".retries," << name << ".reconnects";
  }
  // Live controls: each one's raw value as the tick read it (empty before it first moved).
  const std::size_t controls = live ? live->inputs().mailbox().size() : 0;
  for (std::size_t k = 0; k < controls; ++k) csv << ",input." << live->inputs().mailbox().name(k);
  for (const TraceColumn& c : extra) csv << ',' << c.name;
  csv << '\n' << std::setprecision(9);
  const std::size_t n = rig.channels.size();
  for (std::size_t k = 0; k < r.seconds().size(); ++k) {
    csv << r.seconds()[k] << ',' << control::to_string(r.phase_per_tick()[k]) << ',' << r.lateness()[k] * 1e6;
    for (std::size_t s = 0; s < control::kStageCount; ++s) {
      const std::int64_t ns = r.stage_ns()[k * control::kStageCount + s];
      csv << ',';
      if (ns > 0) csv << static_cast<double>(ns) / 1e3;  // empty when not timed (--fast)
    }
    for (std::size_t i = 0; i < n; ++i) {
      csv << ',' << r.targets()[k * n + i] << ',' << r.commands()[k * n + i] << ',';
      const double m = r.measured()[k * n + i];
      if (!std::isnan(m)) csv << m;
      if (!reported[i]) continue;
      const firmware_iface::ChannelTelemetry& t = r.telemetry()[k * n + i];
      csv << ',';
      if (std::isfinite(t.load)) csv << t.load;
      csv << ',';
      if (std::isfinite(t.temperature_c)) csv << t.temperature_c;
      csv << ',' << t.faults;
    }
    for (std::size_t l : counted_links) {
      const firmware_iface::LinkCounters& w = r.link_counters()[k * rig.links.size() + l];
      csv << ',' << w.replies << ',' << w.crc_errors << ',' << w.framing_errors << ',' << w.timeouts << ',' << w.retries << ','
          << w.reconnects;
    }
    for (std::size_t j = 0; j < controls; ++j) {
      csv << ',';
      if (const double v = r.controls()[k * controls + j]; !std::isnan(v)) csv << v;
    }
    for (const TraceColumn& c : extra) {
      csv << ',';
      if (k < c.values.size() && !std::isnan(c.values[k])) csv << std::setprecision(12) << c.values[k] << std::setprecision(9);
    }
    csv << '\n';
  }
  if (!csv) throw std::runtime_error("cannot write trace file " + path);
}

void write_plot(const std::string& path, const Loaded& loaded, const PlayRecorder& r) {
  PlotData data;
  data.title = "avar play: " + loaded.show.name + " on " + loaded.rig.name;
  data.seconds = r.seconds();
  const std::size_t n = loaded.rig.channels.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = loaded.rig.channels[i];
    PlotChannel ch{c.name, c.unit, c.min, c.max, {}, {}};
    ch.commanded.reserve(data.seconds.size());
    for (std::size_t k = 0; k < data.seconds.size(); ++k) ch.commanded.push_back(r.commands()[k * n + i]);
    if (r.has_measurements())
      for (std::size_t k = 0; k < data.seconds.size(); ++k) ch.measured.push_back(r.measured()[k * n + i]);
    data.channels.push_back(std::move(ch));
  }
  for (const PhaseMark& p : r.phases())
    if (p.phase != control::Phase::disabled) data.markers.emplace_back(p.time_s, control::to_string(p.phase));
  write_svg_plot_file(path, data);
}

}  // namespace

int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err) {
  std::optional<Loaded> loaded = load_and_check(options, err);
  if (!loaded) return kExitBadInput;
  const rig::Rig& rig = loaded->rig;
  // `avar idle` is a live-only run that needs no input device.
  const bool performs = (options.live_only && !options.idle) || options.record_path;
  std::vector<std::string> uris = options.inputs;
  if (uris.empty() && performs) uris = loaded->inputs.devices;
  if (performs && uris.empty() && !session::has_control_inputs(rig)) {
    err << "error: no input device: give --input (osc://127.0.0.1:9000, midi:NAME, hid:VID:PID) or list devices: in the inputs: "
           "section\n";
    return kExitBadInput;
  }
  if (options.record_merge && options.live_only) {
    err << "error: --merge puts the take on a layer over a show; give --show SHOW\n";
    return kExitBadInput;
  }
  if (!uris.empty() && options.fast) {
    err << "error: live inputs need the wall clock; drop --fast\n";
    return kExitBadInput;
  }

  const double rate = options.rate_hz.value_or(rig.rate_hz);
  if (!(rate >= 1 && rate <= 1000)) {
    err << "error: --rate " << rate << " is outside 1 to 1000 ticks per second\n";
    return kExitBadInput;
  }
  if (options.fast && !std::isfinite(loaded->show.duration)) {
    err << "error: --fast cannot run forever; give --duration S\n";
    return kExitBadInput;
  }
  if (loaded->show.loop && options.fast && options.loops.value_or(1) == 0) {
    err << "error: --fast cannot play a looping show forever; give --loops N\n";
    return kExitBadInput;
  }

  session::FigureRunSetup setup;
  setup.session.rate_hz = rate;
  setup.session.stepped = options.fast;
  setup.session.links.port = options.port;
  setup.session.links.simulate_all = options.simulate;
  setup.session.loops = options.loops.value_or(options.fast ? 1 : 0);
  setup.session.realtime = options.realtime;
  setup.session.deadline_miss_budget = options.deadline_miss_budget;
  setup.input_uris = uris;
  if (options.idle) {
    setup.idle_seed = options.seed.value_or(fresh_idle_seed());
    setup.session.lead_in_s = options.idle_before_s;
    setup.session.lead_out_s = options.idle_after_s;
  }
  setup.show_control = options.timecode;
  const double lead_s = setup.session.lead_in_s + setup.session.lead_out_s;
  const std::uint64_t loops = setup.session.loops;

  // Everything opens before anything moves: a missing device, a busy port or a bad spec stops
  // the run here.
  std::unique_ptr<session::FigureRun> figure_run;
  try {
    figure_run = std::make_unique<session::FigureRun>(rig, loaded->show, loaded->inputs, std::move(setup));
  } catch (const session::NeedsSimulatedLinks&) {
    err << "error: --fast runs on a simulated clock and needs every link simulated; drop --port or add --sim\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  session::FigureRun& fr = *figure_run;
  if (options.record_path && !fr.live()) {
    // The rig's control buttons open no live inputs without mappings: nothing could be performed.
    err << "error: nothing to record: no live control reaches a channel; give --input, or map the rig's control inputs in "
           "the inputs: section's mappings\n";
    return kExitBadInput;
  }

  // Digital inputs watch from here on: the e-stop before anything moves, control inputs into the
  // live mixer, start buttons for --wait-start.
  try {
    fr.watch_inputs();
  } catch (const std::runtime_error& e) {
    err << "error: " << e.what() << '\n';
    return kExitFault;
  }
  if (options.wait_start) {
    InterruptCounter waiting;
    if (const std::string buttons = fr.start_button_names(); !buttons.empty())
      err << "waiting for start button " << buttons << "; Ctrl-C gives up" << std::endl;
    switch (fr.wait_for_start_button(waiting.count())) {
      case session::StartWait::pressed: break;
      case session::StartWait::interrupted:
        err << "stopped before the start button was pressed; nothing moved\n";
        return kExitInterrupted;
      case session::StartWait::estop: err << "e-stop is pressed; release it and reset before starting\n"; return kExitFault;
      case session::StartWait::no_button:
        err << "error: --wait-start needs a digital input with role: start in the rig (digital_inputs:)\n";
        return kExitBadInput;
    }
  }

  session::ShowSession& session = fr.session();
  if (const std::optional<session::LinkProblem> p = fr.start()) {
    err << "error: " << session.figure().links()[p->link]->describe() << " did not start: " << to_string(p->status)
        << (p->problem.empty() ? "" : ": " + p->problem) << " (check power, cable, the device's serial mode and the baud rate)\n";
    return kExitFault;
  }
  const control::Controller& controller = session.controller();
  const assembly::FigureLinks& figure = session.figure();
  const LiveSession* live = fr.live();

  const bool keep = options.trace_path || options.plot_path || options.record_path;
  const double passes = loaded->show.loop ? static_cast<double>(std::max<std::uint64_t>(loops, 1)) : 1.0;
  // A live run without an end reserves a minute; longer ones grow as they go.
  const double planned_s = std::isfinite(loaded->show.duration) ? passes * loaded->show.duration + lead_s : 60.0;
  const auto expected_ticks = static_cast<std::size_t>((planned_s + 10.0) * rate);
  const bool realtime = !options.fast;
  const bool show_progress = options.progress && realtime;
  session::RecorderOptions recording;
  recording.channels = rig.channels.size();
  recording.links = rig.links.size();
  recording.controls = fr.recorded_controls();
  recording.show_duration_s = loaded->show.duration;
  recording.keep_samples = keep;
  recording.expected_ticks = expected_ticks;
  recording.progress = show_progress ? &err : nullptr;
  recording.progress_is_terminal = ::isatty(STDERR_FILENO) == 1;
  recording.notices = &err;
  PlayRecorder recorder(recording);
  session.add_observer(recorder);

  // Signals count from here on: a Ctrl-C from now eases the figure to rest.
  InterruptCounter interrupts;
  if (options.live_only)
    err << (options.idle ? "idle on '" : "live on '") << rig.name << "'"
        << (std::isfinite(loaded->show.duration) ? " for " + format_number(loaded->show.duration) + " s" : std::string())
        << (options.record_path ? ", recording" : "") << "; Ctrl-C " << (options.record_path ? "ends the take and " : "")
        << "eases to rest, twice releases; Ctrl-\\ is an e-stop" << std::endl;
  else
    err << "playing '" << loaded->show.name << "' (" << loaded->show.duration << " s" << (loaded->show.loop ? ", looping" : "")
        << ") on '" << rig.name << "'" << (options.record_path ? ", recording" : "")
        << (realtime ? "; Ctrl-C eases to rest, twice releases; Ctrl-\\ is an e-stop" : "") << std::endl;
  if (const OscControlSurface* surface = fr.surface())
    err << "OSC control on udp " << surface->where() << ": waiting for /avar/show/play '" << loaded->show.name << "'"
        << std::endl;
  const control::RunResult run = fr.run(interrupts.count(), &interrupts.estop());
  recorder.finish(controller);
  if (fr.cues().osc_cues() > 0)
    err << "cues: " << fr.cues().sent() << " OSC message(s) sent, " << fr.cues().failed() << " failed\n";
  for (const std::string& w : run.realtime.warnings) err << "warning: " << w << '\n';

  print_summary(out, *loaded, figure, controller, recorder, run, realtime, rate, live);
  if (const IdleSession* idle = fr.idle()) idle->describe(out);
  if (const TimecodeRun* chase = fr.chase()) chase->summarize(out);
  if (const OscControlSurface* surface = fr.surface()) surface->summarize(out);
  try {
    if (options.record_path) {
      const session::TakeReport take = session::write_take({*options.record_path, options.record_tolerance, options.record_merge},
                                                           rig, loaded->show, controller, recorder, live->inputs());
      out << "take: " << format_number(take.duration_s) << " s, " << take.ticks << " ticks\n";
      for (const session::TakeTrack& t : take.tracks)
        out << "  " << t.channel << ": " << t.keys << " keys, max error " << format_number(t.max_error) << " (tolerance "
            << format_number(options.record_tolerance) << ")\n";
      out << "wrote " << *options.record_path << (options.record_merge ? " (the show with the take on layer 'take')" : "")
          << '\n';
    }
    if (options.trace_path) {
      write_trace(*options.trace_path, rig, figure, recorder, live,
                  fr.chase() ? fr.chase()->trace_columns() : std::vector<TraceColumn>{});
      out << "trace: " << *options.trace_path << '\n';
    }
    if (options.plot_path) {
      write_plot(*options.plot_path, *loaded, recorder);
      out << "plot: " << *options.plot_path << '\n';
    }
  } catch (const std::exception& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }

  const control::Fault& fault = controller.latched_fault();
  if (fault.cause != control::FaultCause::none) {
    const bool about_link = fault.cause == control::FaultCause::link_watchdog || fault.cause == control::FaultCause::link_failure;
    const bool about_channel =
        fault.cause == control::FaultCause::tracking_error || fault.cause == control::FaultCause::non_finite ||
        fault.cause == control::FaultCause::device_overheat || fault.cause == control::FaultCause::device_overload ||
        fault.cause == control::FaultCause::device_error || fault.cause == control::FaultCause::device_lost;
    err << "fault at " << format_fixed(fault.time_s, 3) << " s while " << control::to_string(fault.from) << ": "
        << control::to_string(fault.cause);
    if (about_link) err << " on link " << rig.links[fault.index].name << " (" << to_string(fault.status) << ")";
    if (about_channel) err << " on channel " << rig.channels[fault.index].name;
    if (about_channel)
      if (const std::string problem = figure.channel_problem(fault.index); !problem.empty()) err << " (" << problem << ")";
    if (fault.cause == control::FaultCause::tracking_error) err << " (error " << format_fixed(fault.value, 3) << ")";
    if (fault.cause == control::FaultCause::deadline_budget) err << " (" << fault.value << " misses)";
    err << "; actuators took their fail-safe actions (hold, rest or release, from the rig)\n";
    return kExitFault;
  }
  if (run.released) {
    err << "released: every actuator was let go at once (second interrupt)\n";
    return kExitInterrupted;
  }
  if (run.interrupted) {
    err << "stopped: eased to rest after an interrupt\n";
    // Ctrl-C is how a take ends: the take is kept and that is success.
    return options.record_path ? kExitOk : kExitInterrupted;
  }
  return kExitOk;
}

}  // namespace avar::app
