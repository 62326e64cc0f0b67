#include "avar/timecode_options.hpp"

#include <CLI/CLI.hpp>

namespace avar::app {

void declare_show_control_options(CLI::App* cmd, session::ShowControlOptions& o) {
  cmd->add_option(
      "--timecode", o.source,
      "Chase a timecode source: ltc:FILE.wav, ltc:alsa:DEVICE, mtc:PORT, artnet[:PORT] or artnet:HOST:PORT (show time follows "
      "it; the run stops when it is gone for --freewheel seconds)");
  cmd->add_option("--offset", o.offset, "Timecode at show time 0, HH:MM:SS:FF (default 00:00:00:00)");
  cmd->add_option("--freewheel", o.freewheel_s, "Seconds to run on without timecode before easing to rest (default 2)")
      ->check(CLI::Range(0.0, 3600.0));
  cmd->add_option("--osc-control", o.osc_control,
                  "OSC control surface on UDP [ADDRESS:]PORT (127.0.0.1 unless given): the show waits for "
                  "/avar/show/play NAME; /avar/show/stop, /avar/show/seek SECONDS, /avar/estop, /avar/state");
}

}  // namespace avar::app
