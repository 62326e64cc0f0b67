#pragma once
// Input devices by URI: osc://HOST:PORT, midi:NAME, hid:VID:PID[:SERIAL], each optionally
// prefixed NAME= to prefix its controls' names.

#include <memory>
#include <string_view>

#include "avar/firmware_iface/input_source.hpp"

namespace avar::firmware_iface {

/// The (not yet started) input source for `uri`. Throws std::invalid_argument with a message
/// teaching the accepted forms.
std::unique_ptr<InputSource> make_input_source(std::string_view uri);

}  // namespace avar::firmware_iface
