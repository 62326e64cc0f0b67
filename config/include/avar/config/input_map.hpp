#pragma once
// The `inputs:` section of a rig file, or of an inputs file of its own: which input devices to
// open and how their controls drive the rig's channels (avar::control::ControlMapping). Read
// and validated whole before anything moves; errors are InputErrors with file, line and column.
//
//   inputs:
//     devices: [osc://127.0.0.1:9000, "midi:nanoKONTROL"]   # opened by play/puppet/record
//     mappings:
//       - control: ch1.cc0          # as the device names it (see the README)
//         channel: jaw
//         mode: absolute            # absolute (default) | relative
//         range: [0, 35]            # absolute: output range in channel units; default the limits
//                                   # (additive: an offset range, default [0, max - min])
//         rate: 90                  # relative: channel units/s at full deflection (required)
//         input: [0, 127]           # raw values that span the control (default: its normalised range)
//         invert: false
//         dead_zone: 0.05           # 0 to below 1
//         expo: 0.3                 # 0 (linear) to 1 (cubic)
//         smoothing: 0.05           # low-pass time constant, s
//         hold: button5             # active only while this control reads >= 0.5
//         priority: 10              # higher wins; the direct channel/NAME controls sit at 1000
//         blend: override           # override | additive
//         crossfade: 0.3            # s, hand-over both ways
//         timeout: 2                # s without a message before handing back; 0 = never
//       - control: x                # or: one axis of an inverse-kinematics target
//         target: head              # an effector of the rig's kinematics
//         axis: y                   # x | y | z, the rig's base frame
//         range: [-0.4, 0.4]        # metres (required): absolute: the span; relative: the bounds
//         mode: relative            # relative: rate in m/s
//         rate: 0.5

#include <string>
#include <vector>

#include "avar/control/live_inputs.hpp"
#include "avar/core/input_error.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

struct InputMap {
  std::vector<std::string> devices;  ///< input URIs as written
  std::vector<control::ControlMapping> mappings;
  std::vector<SourceLocation> mapping_where;  ///< per mapping
  std::string file;                           ///< where it was read from; empty: nowhere
};

/// The `inputs:` section of `path` (a rig file, whose other keys the rig loader checks, or an
/// inputs file with `inputs:` only), checked against `rig`. `required`: a file without the
/// section is an error (an inputs file given on the command line); otherwise an empty map.
InputMap load_input_map(const rig::Rig& rig, const std::string& path, bool required);

/// The rig's channels as LiveInputs takes them.
std::vector<control::LiveChannel> live_channels(const rig::Rig& rig);
/// The rig's kinematic effectors' names, in the model's order, as LiveInputs takes them (none
/// without a kinematics section).
std::vector<std::string> live_effectors(const rig::Rig& rig);

}  // namespace avar::config
