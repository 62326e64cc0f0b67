#pragma once
// OSC messages as controls (pure: no I/O, no allocation). Two addresses:
//
//   /avar/control/NAME  one number  -> control "NAME" (a unipolar 0..1 control by convention;
//                                      the value is passed on as sent, the mapping stage clamps)
//   /avar/channel/NAME  one number  -> control "channel/NAME", the value in the channel's own
//                                      units (degrees, mm, ...), not normalised
//
// The number may be any of the OSC types f (float32), d (float64), i (int32), h (int64), or T/F
// (true/false, no data: 1/0). Ignored: any other address, no argument or more than one, any other
// type, a non-finite value (NaN, inf), and a NAME that is empty, longer than kMaxOscControlName or
// has characters outside [A-Za-z0-9_.-].

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace avar::inputs {

inline constexpr std::string_view kOscControlPrefix = "/avar/control/";
inline constexpr std::string_view kOscChannelPrefix = "/avar/channel/";
/// Controls named from OSC channels start with this ("channel/jaw").
inline constexpr std::string_view kOscChannelControlPrefix = "channel/";
inline constexpr std::size_t kMaxOscControlName = 128;

struct OscControl {
  std::string_view control;  ///< "jaw" or "channel/jaw": a view into the path given
  double value = 0;
};

/// The control an OSC message sets, or nullopt when it is ignored. `types` is the message's type
/// tag string without the leading ',' ("f"); `values[i]` is argument i as a number, read only for
/// the numeric types (precondition: values.size() == types.size()). Real-time safe; any thread.
std::optional<OscControl> osc_control(std::string_view path, std::string_view types, std::span<const double> values) noexcept;

}  // namespace avar::inputs
