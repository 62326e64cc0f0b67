#pragma once
// Input devices by URI, as `--input` and an inputs section's `devices:` name them:
//
//   osc://HOST:PORT   OSC over UDP on an IPv4 address: osc://:9000 and osc://localhost:9000
//                     listen on 127.0.0.1 only, osc://0.0.0.0:9000 on every interface; no port:
//                     9000; port 0: any free port (OscInput::bound_port() tells which)
//   midi:NAME         a MIDI input port: a case-insensitive part of its name (midi:nano) or its
//                     number (midi:1)
//   hid:VID:PID[:SERIAL]  a HID gamepad or joystick, hex ids (hid_input.hpp)
//   NAME=URI          the same device, its controls named NAME.control (pad=hid:054c:09cc turns
//                     "x" into "pad.x"); NAME of letters, digits, '_' and '-'. OSC's direct
//                     channel controls ("channel/jaw") keep their names: they name the rig's
//                     channels, not the device's controls.

#include <memory>
#include <string_view>

#include "avar/inputs/input_source.hpp"

namespace avar::inputs {

/// The accepted forms, for error messages.
extern const std::string_view kInputSourceForms;

/// The (not yet started) input source for `uri`: nothing is opened until start(). Throws
/// std::invalid_argument naming the URI and teaching the accepted forms when it is not one of them.
std::unique_ptr<InputSource> make_input_source(std::string_view uri);

}  // namespace avar::inputs
