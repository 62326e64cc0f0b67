#pragma once
// Reading the tracks of a show file: keys, handles, easing, extrapolation and cycles. Internal to
// config/: every reader of a show-file section that holds keyframe curves uses these, so one
// curve is written the same way wherever it appears. Load time: allocates, throws InputError.

#include <string>
#include <string_view>

#include "yaml_support.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config::detail {

/// A name from one of the vocabularies (interpolation, easing, ...), parsed by `parse` (returns
/// an optional), or a failure at the node listing the accepted names.
template <typename Parse>
auto read_name(const YamlRef& node, std::string_view what, Parse parse, std::string_view accepted) {
  const auto parsed = parse(node.as_string(what));
  if (!parsed) node.fail("unknown " + std::string(what) + " " + node.describe() + "; expected one of: " + std::string(accepted));
  return *parsed;
}

/// One track: `name` is the channel (the YAML key), `body` a list of keys or a map {extrapolation,
/// cycles, auto_smoothing, keys}. Key times may lie outside the span that plays (before 0 or
/// after the show's end, as Blender scenes keyed from frame 0 export them): they shape the curve
/// inside it.
/// `span_s`: the show's (or clip's) duration, where a track made from audio is cut.
playback::Track read_track(const YamlRef& name, const YamlRef& body, double span_s);

/// One key map of a track of `channel`; `previous` is the interpolation of the key before it
/// (in_slope belongs only after a hermite key), nullopt for the first.
playback::RawKey read_key(const YamlRef& node, const std::string& channel, std::optional<playback::Interpolation> previous);

/// The `time` of a key map (`what` names the key), in seconds: any finite number.
double read_key_time(const YamlRef& key, std::string_view what);

/// A constant one-key curve of `value`, for a static quantity; `raw` receives its keys.
playback::Curve constant_curve(double value, const SourceLocation& where, playback::RawCurve& raw);

}  // namespace avar::config::detail
