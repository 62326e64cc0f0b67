#pragma once
// A show: tracks of keyframe curves, each bound by name to a channel of a rig, played over a
// duration, once or looping; optionally clips placed on layers over those tracks (timeline.hpp).

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/clip.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/orientation_keys.hpp"
#include "avar/playback/runtime/path_track.hpp"
#include "avar/playback/runtime/timeline.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::playback {

/// What an effector of the rig's kinematics is asked to do.
enum class TargetKind {
  position,     ///< bring the effector's origin to the point
  aim,          ///< point the effector-frame axis `aim_axis` at the point (eyes, heads, lights)
  orientation,  ///< turn the effector frame to the orientation
  pose,         ///< both the point and the orientation
};

/// A target for one effector, solved by inverse kinematics every tick. The point's x, y and z
/// (metres, in the rig's base frame) and the orientation's roll, pitch and yaw (radians: the
/// effector frame turned about the base's fixed x, then y, then z axes, as URDF's rpy) are
/// keyframe curves; a static value is a one-key curve. Instead of x, y, z curves the point may
/// follow a path (PathTrack), which may also give the orientation; instead of roll, pitch, yaw
/// curves the orientation may come from quaternion or Euler keys (OrientationKeyTrack).
struct TargetTrack {
  std::string effector;  ///< effector name in the rig's kinematics
  TargetKind kind = TargetKind::position;
  std::array<double, 3> aim_axis{1, 0, 0};              ///< effector frame, any non-zero length (aim only)
  std::array<RawCurve, 3> raw;                          ///< x, y, z as authored (position, aim, pose)
  std::array<Curve, 3> xyz;                             ///< built from raw
  std::array<RawCurve, 3> raw_rpy;                      ///< roll, pitch, yaw as authored (orientation, pose)
  std::array<Curve, 3> rpy;                             ///< built from raw_rpy
  std::optional<PathTrack> path;                        ///< when set, the point (and, if it orients, the orientation)
  std::optional<OrientationKeyTrack> orientation_keys;  ///< when set, the orientation
  SourceLocation where;

  bool has_point() const noexcept { return kind != TargetKind::orientation; }
  bool has_orientation() const noexcept { return kind == TargetKind::orientation || kind == TargetKind::pose; }
};

/// One argument of an OSC cue's message.
struct CueArgument {
  char type = 'f';  ///< 'f' float, 'i' 32-bit integer, 's' string
  double number = 0;
  std::string text;
};

/// Something a show fires once at a time of each pass (`cues:` in a show file): an OSC message
/// to a UDP address, or a digital channel switched (played as a step track of that channel, so
/// the limiter, safety gate and fail-safe apply to it as to any channel).
struct Cue {
  double time = 0;       ///< seconds within the show
  std::string osc_host;  ///< OSC: numeric IPv4 address ("" for a digital cue)
  int osc_port = 0;
  std::string osc_address;  ///< OSC: "/path"
  std::vector<CueArgument> osc_arguments;
  std::string digital_channel;  ///< digital: the channel switched
  double digital_value = 0;     ///< digital: 0 off, 1 on
  SourceLocation where;

  bool is_osc() const noexcept { return !osc_address.empty(); }
};

/// A named point of a show's time (`markers:` in a show file): where an animator navigates to
/// and what an editor shows on its ruler; it plays nothing.
struct Marker {
  double time = 0;  ///< seconds within the show
  std::string name;
  SourceLocation where;
};

struct Show {
  std::string name;
  double duration = 0;  ///< seconds, > 0
  bool loop = false;
  std::vector<Track> tracks;
  std::vector<TargetTrack> targets;
  std::vector<Clip> clips;    ///< the clips the layers place (none for a plain show)
  std::vector<Layer> layers;  ///< applied bottom (first) to top over `tracks`; none for a plain show
  std::vector<Cue> cues;      ///< in time order
  std::vector<Marker> markers;  ///< in time order, names unique
  SourceLocation where;

  bool layered() const noexcept { return !layers.empty(); }

  /// The time within the show's curves for playing time t (seconds): a looping show wraps t
  /// modulo its duration (negative times included); a show played once passes t through (its
  /// curves hold their end values outside the keys). Real-time safe.
  double local_time(double t) const noexcept {
    if (!loop || !(duration > 0)) return t;
    const double w = std::fmod(t, duration);
    return w < 0 ? w + duration : w;
  }
};

}  // namespace avar::playback
