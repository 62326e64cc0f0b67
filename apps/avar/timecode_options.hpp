#pragma once
// The command-line options of show time: --timecode, --offset, --freewheel (a chased timecode
// source, session/timecode_run.hpp) and --osc-control (the OSC control surface,
// session/osc_control.hpp).

#include "avar/session/timecode_run.hpp"

namespace CLI {
class App;
}

namespace avar::app {

/// Adds --timecode, --offset, --freewheel and --osc-control to `cmd`.
void declare_show_control_options(CLI::App* cmd, session::ShowControlOptions& o);

}  // namespace avar::app
