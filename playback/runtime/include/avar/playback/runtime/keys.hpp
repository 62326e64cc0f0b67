#pragma once
// Keys as authored: the vocabulary of interpolations, easings, handles, extrapolation and cycles,
// and the editable curve (RawCurve) that Curve::build turns into a runtime curve. Plain data, no
// logic: the runtime show keeps them beside its built curves (Track::raw, for checks and reports),
// and the offline layer reads them to validate and build. Times in seconds, values in channel units.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "avar/core/bit_cast.hpp"
#include "avar/core/input_error.hpp"

namespace avar::playback {

/// How the segment that starts at a key is shaped. `step` is Blender's CONSTANT.
enum class Interpolation : std::uint8_t {
  step,
  linear,
  bezier,
  // Blender's easing families (Robert Penner's equations as blenlib easing.cc has them).
  sine,
  quad,
  cubic,
  quart,
  quint,
  expo,
  circ,
  back,
  bounce,
  elastic,
  // avar's own cubic splines.
  hermite,           ///< cubic Hermite with the keys' explicit out_slope / in_slope (units per second)
  catmull_rom,       ///< tangent at a key: mean of the slopes of its two neighbouring chords
  cardinal,          ///< Catmull-Rom tangents scaled by (1 - tension)
  kochanek_bartels,  ///< tension, continuity, bias (TCB) tangents
  bspline,           ///< uniform cubic B-spline with the key values as control points
};

/// Which end of an easing segment eases. `automatic` is Blender's AUTO: ease_out for back,
/// bounce and elastic, ease_in for the others.
enum class Easing : std::uint8_t { automatic, ease_in, ease_out, ease_in_out };

/// Blender's Bezier handle types, per side of a key.
enum class HandleType : std::uint8_t { free, aligned, vector, automatic, auto_clamped };

/// Outside the keys: hold the end value, or continue along the end slope (Blender's rules).
enum class Extrapolation : std::uint8_t { constant, linear };

/// Blender's auto-handle smoothing: none, or "continuous acceleration".
enum class AutoSmoothing : std::uint8_t { none, continuous_acceleration };

/// One side of a Cycles modifier.
enum class CycleMode : std::uint8_t { none, repeat, repeat_offset, mirror };

/// "constant" (also "step"), "linear", "bezier", "sine", ... "bspline"; nullopt for anything else.
std::optional<Interpolation> interpolation_from_name(std::string_view name);
std::optional<Easing> easing_from_name(std::string_view name);                 ///< auto, ease_in, ease_out, ease_in_out
std::optional<HandleType> handle_type_from_name(std::string_view name);        ///< free, aligned, vector, auto, auto_clamped
std::optional<Extrapolation> extrapolation_from_name(std::string_view name);   ///< constant, linear
std::optional<AutoSmoothing> auto_smoothing_from_name(std::string_view name);  ///< none, continuous_acceleration
std::optional<CycleMode> cycle_mode_from_name(std::string_view name);          ///< none, repeat, repeat_offset, mirror
/// The names the *_from_name functions accept (the canonical one where there are aliases).
const char* to_string(Interpolation interpolation);
const char* to_string(Easing easing);
const char* to_string(HandleType type);
const char* to_string(Extrapolation extrapolation);
const char* to_string(AutoSmoothing smoothing);
const char* to_string(CycleMode mode);
/// Every accepted name, comma separated, for error messages.
const char* interpolation_names();
/// The canonical names, in the show file's order (an editor's menus).
std::vector<std::string_view> interpolation_name_list();
std::vector<std::string_view> easing_name_list();
std::vector<std::string_view> handle_type_name_list();
std::vector<std::string_view> extrapolation_name_list();
bool is_easing_family(Interpolation interpolation);

/// A Bezier handle, absolute: (seconds, channel units).
struct Handle {
  double time = 0;
  double value = 0;
};

/// Whether two handles are the same: both absent, or the same bits (results built from them must
/// be bit-identical).
inline bool same_handle(const std::optional<Handle>& a, const std::optional<Handle>& b) noexcept {
  return a.has_value() == b.has_value() && (!a || (same_bits(a->time, b->time) && same_bits(a->value, b->value)));
}

struct RawKey {
  double time = 0;                                      ///< seconds
  double value = 0;                                     ///< channel units
  Interpolation interpolation = Interpolation::linear;  ///< of the segment from this key to the next
  /// Handles. A side without a type is `free` when its handle is given and `auto_clamped`
  /// (Blender's default) when not; free and aligned sides need their handle, the others compute it.
  std::optional<Handle> left;
  std::optional<Handle> right;
  std::optional<HandleType> left_type;
  std::optional<HandleType> right_type;
  Easing easing = Easing::automatic;  ///< easing families only
  double back = 1.70158;              ///< back: overshoot (Blender's default)
  double amplitude = 0;               ///< elastic: channel units; below |change| Blender's blend scales the wave
  double period = 0;                  ///< elastic: seconds; 0 = Blender's default (0.3 of the segment)
  std::optional<double> in_slope;     ///< hermite: slope arriving at this key (units per second)
  std::optional<double> out_slope;    ///< hermite: slope leaving this key (units per second)
  double tension = 0;                 ///< cardinal, kochanek_bartels: this key's tangent
  double continuity = 0;              ///< kochanek_bartels
  double bias = 0;                    ///< kochanek_bartels
  SourceLocation where;
};

/// Blender's Cycles F-modifier: how each side repeats the keyed range, and how many times
/// (0 = forever). Past the count the curve extrapolates from the real time, as in Blender.
struct Cycles {
  CycleMode before = CycleMode::none;
  CycleMode after = CycleMode::none;
  int before_count = 0;
  int after_count = 0;
  bool any() const noexcept { return before != CycleMode::none || after != CycleMode::none; }
};

/// The sound a curve was made from (a jaw following a voice): what an editor shows beside it.
struct AudioSource {
  std::string path;    ///< the sound file, as the show file's folder resolves it
  double start_s = 0;  ///< show time where the sound begins
};

struct RawCurve {
  RawCurve() = default;
  RawCurve(std::vector<RawKey> keys_in, SourceLocation where_in) : keys(std::move(keys_in)), where(std::move(where_in)) {}

  std::vector<RawKey> keys;
  SourceLocation where;
  Extrapolation extrapolation = Extrapolation::constant;
  AutoSmoothing auto_smoothing = AutoSmoothing::none;
  Cycles cycles;
  /// Keys made from a sound file (a jaw track's `audio`): that sound. The keys alone make the curve.
  std::optional<AudioSource> audio;
};

}  // namespace avar::playback
