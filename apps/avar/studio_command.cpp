#include "avar/studio_command.hpp"

#include <spawn.h>
#include <unistd.h>
#include <sys/wait.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "avar/exit_codes.hpp"
#include "avar/interrupts.hpp"
#include "avar/studio/studio_run.hpp"

namespace avar::app {
namespace {

/// Hands the URL to the desktop's browser (xdg-open); false when there is none.
bool open_in_browser(const std::string& url) {
  pid_t pid = 0;
  std::string program = "xdg-open";
  char* argv[] = {program.data(), const_cast<char*>(url.c_str()), nullptr};
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv, environ) != 0) return false;
  int status = 0;
  return waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

CLI::App* add_studio_subcommand(CLI::App& app, StudioOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "studio", "Serve the studio: pose the figure, scrub and edit its show from a browser page or any program");
  cmd->add_option("show", o.show_path,
                  "Show file to edit and save (YAML); a path that does not exist is a new show, made when you save; "
                  "none: a new show that cannot be saved");
  cmd->add_option("--rig", o.rig_path, "Rig file (YAML: channels, limits, links)")->required();
  CLI::Option* sim = cmd->add_flag("--sim", o.simulate, "Simulate every link: the simulator answers with the same bytes");
  cmd->add_option("--port", o.port, "Serial port of the rig's single link, instead of the rig file's")->excludes(sim);
  cmd->add_option("--rate", o.rate_hz, "Ticks per second, 1 to 1000 (default: the rig's rate_hz)");
  cmd->add_option("--listen", o.listen,
                  "HOST:PORT to serve on (default 127.0.0.1:0: this machine only, a free port). Any address but loopback "
                  "needs the token printed in the URL");
  cmd->add_flag("--open", o.open_browser, "Open the URL in the desktop's browser (xdg-open)");
  cmd->add_option("--input", o.inputs,
                  "Live input device, repeatable: osc://HOST:PORT, midi:NAME, hid:VID:PID[:SERIAL] (as for avar puppet); "
                  "its mapped controls pose channels and steer the show's IK targets while you edit");
  cmd->add_option("--inputs", o.inputs_path,
                  "Inputs file (YAML with an inputs: section; default: the rig's own inputs:); without --input, its "
                  "devices: are opened");
  cmd->add_option("--page", o.page_dir, "Serve the browser page from this folder instead of the one built with avar")
      ->check(CLI::ExistingDirectory);
  cmd->footer(
      "Open the printed URL in a browser: sliders pose the figure, the timeline scrubs it, the dope sheet and\n"
      "the graph editor edit the show. The figure homes to the show's first frame and waits, paused.\n"
      "Programs connect to ws://HOST:PORT/ws and speak the studio protocol (docs: reference/studio-protocol):\n"
      "play, pause, seek, scrub, loop; hold a channel at a value (a slider) and release it; edit keys, insert and\n"
      "delete time; undo, redo, save; stop; e-stop.\n"
      "Whatever a client asks, the figure obeys the rig's limits and glides, never snaps; edits reach it at the\n"
      "next tick. The show holds its end instead of ending; Ctrl-C eases to rest and stops.\n"
      "Examples:\n"
      "  avar studio examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml --sim\n"
      "      edit the bundled show on the simulated head; the URL is printed\n"
      "  avar studio my-show.yaml --rig my-rig.yaml --port /dev/ttyACM0 --listen 0.0.0.0:8080\n"
      "      on the real figure, reachable from the workshop's network with the printed token\n"
      "  avar studio examples/shows/look-around.yaml --rig examples/rigs/gaze-head.yaml --sim \\\n"
      "      --inputs examples/inputs/gaze-head-stick.yaml\n"
      "      steer the head's gaze target from OSC (/avar/control/gaze_y 0.9 on port 9000) while you edit");
  return cmd;
}

int run_studio(const StudioOptions& o, std::ostream& out, std::ostream& err) {
  studio::StudioSetup setup;
  try {
    studio::parse_listen_address(o.listen, setup.server);
    setup.server.assets_dir = o.page_dir.value_or(studio::built_page_dir());
  } catch (const std::invalid_argument& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  std::optional<studio::StudioFiles> files;
  try {
    files.emplace(studio::open_studio_files(o.rig_path, o.show_path, o.inputs_path));
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  for (const auto& w : files->check.warnings) err << "warning: " << w.to_string() << '\n';
  for (const auto& e : files->check.errors) err << "error: " << e.to_string() << '\n';
  if (!files->check.ok()) return kExitBadInput;
  if (files->new_file) err << "new show: " << *o.show_path << " is made when you save\n";
  const rig::Rig& rig = files->rig;
  setup.run.session.rate_hz = o.rate_hz.value_or(rig.rate_hz);
  setup.run.session.links.simulate_all = o.simulate;
  setup.run.session.links.port = o.port;
  // Live devices open only when asked: a rig's listed gamepad need not be plugged in to edit.
  setup.run.input_uris = !o.inputs.empty() ? o.inputs : o.inputs_path ? files->inputs.devices : std::vector<std::string>{};

  std::unique_ptr<studio::StudioRun> run;
  try {
    run = std::make_unique<studio::StudioRun>(rig, files->inputs, std::move(files->document), o.show_path.value_or(""), setup);
  } catch (const std::exception& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  try {
    if (const std::optional<session::LinkProblem> p = run->start()) {
      err << "error: " << run->figure().session().figure().links()[p->link]->describe()
          << " did not start: " << to_string(p->status) << (p->problem.empty() ? "" : ": " + p->problem)
          << " (check power, cable, the device's serial mode and the baud rate)\n";
      return kExitFault;
    }
  } catch (const std::runtime_error& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }

  out << "studio: " << run->url() << '\n'
      << "  figure '" << rig.name << "' " << (o.simulate ? "on the simulator" : "on its links") << ", show '"
      << run->studio().document().show().name << "'" << (o.show_path ? " (" + *o.show_path + ")" : " (no file: save is off)")
      << '\n'
      << "  the protocol: /ws (WebSocket), /api/hello and /api/status (GET); see the studio protocol in the manual\n"
      << "  Ctrl-C eases the figure to rest and stops; Ctrl-\\ is the e-stop" << std::endl;
  if (setup.server.assets_dir.empty())
    err << "warning: the studio's page is not built (make demo or make build builds it; it needs node, npm and "
           "emscripten); /ws and /api still serve\n";
  if (o.open_browser && !open_in_browser(run->url())) err << "could not open a browser (xdg-open); open the URL above\n";

  InterruptCounter interrupts;
  const control::RunResult result = run->run(interrupts.count(), &interrupts.estop());
  const edit::ShowDocument& edited = run->studio().document();
  if (edited.modified())
    err << "warning: the show has changes that were not saved (" << edited.undo_steps() << " undo steps); they are lost\n";
  const control::Fault& fault = run->figure().session().controller().latched_fault();
  if (fault.cause != control::FaultCause::none) {
    err << "fault: " << control::to_string(fault.cause) << "; every actuator took its fail-safe action\n";
    return kExitFault;
  }
  if (result.interrupted) {
    out << "stopped: eased to rest\n";
    return kExitInterrupted;
  }
  out << "stopped: a client asked; eased to rest\n";
  return kExitOk;
}

}  // namespace avar::app
