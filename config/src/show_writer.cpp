#include "avar/config/show_writer.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <vector>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "show_behaviour.hpp"

namespace avar::config {
namespace {

using playback::Interpolation;

/// Enough digits for every double to read back to itself.
constexpr int kDoublePrecision = 17;

bool is_easing(Interpolation i) { return i >= Interpolation::sine && i <= Interpolation::elastic; }

void write_key(YAML::Emitter& y, const playback::RawKey& key, const playback::RawKey* previous) {
  y << YAML::Flow << YAML::BeginMap << YAML::Key << "time" << YAML::Value << key.time << YAML::Key << "value" << YAML::Value
    << key.value;
  if (key.interpolation != Interpolation::linear)
    y << YAML::Key << "interpolation" << YAML::Value << playback::to_string(key.interpolation);
  const auto pair = [&](const char* name, const playback::Handle& h) {
    y << YAML::Key << name << YAML::Value << YAML::Flow << std::vector<double>{h.time, h.value};
  };
  if (key.left) pair("left", *key.left);
  if (key.right) pair("right", *key.right);
  if (key.left_type) y << YAML::Key << "left_type" << YAML::Value << playback::to_string(*key.left_type);
  if (key.right_type) y << YAML::Key << "right_type" << YAML::Value << playback::to_string(*key.right_type);
  if (is_easing(key.interpolation) && key.easing != playback::Easing::automatic)
    y << YAML::Key << "easing" << YAML::Value << playback::to_string(key.easing);
  if (key.interpolation == Interpolation::back) y << YAML::Key << "back" << YAML::Value << key.back;
  if (key.interpolation == Interpolation::elastic)
    y << YAML::Key << "amplitude" << YAML::Value << key.amplitude << YAML::Key << "period" << YAML::Value << key.period;
  if (key.interpolation == Interpolation::cardinal || key.interpolation == Interpolation::kochanek_bartels)
    y << YAML::Key << "tension" << YAML::Value << key.tension;
  if (key.interpolation == Interpolation::kochanek_bartels)
    y << YAML::Key << "continuity" << YAML::Value << key.continuity << YAML::Key << "bias" << YAML::Value << key.bias;
  if (key.interpolation == Interpolation::hermite && key.out_slope)
    y << YAML::Key << "out_slope" << YAML::Value << *key.out_slope;
  if (previous && previous->interpolation == Interpolation::hermite && key.in_slope)
    y << YAML::Key << "in_slope" << YAML::Value << *key.in_slope;
  y << YAML::EndMap;
}

/// A curve: the short form (a list of keys) when it has no curve-wide settings.
void write_curve(YAML::Emitter& y, const playback::RawCurve& raw) {
  const bool long_form = raw.extrapolation != playback::Extrapolation::constant ||
                         raw.auto_smoothing != playback::AutoSmoothing::none || raw.cycles.any();
  if (long_form) {
    y << YAML::BeginMap;
    if (raw.extrapolation != playback::Extrapolation::constant)
      y << YAML::Key << "extrapolation" << YAML::Value << playback::to_string(raw.extrapolation);
    if (raw.auto_smoothing != playback::AutoSmoothing::none)
      y << YAML::Key << "auto_smoothing" << YAML::Value << playback::to_string(raw.auto_smoothing);
    if (raw.cycles.any())
      y << YAML::Key << "cycles" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "before" << YAML::Value
        << playback::to_string(raw.cycles.before) << YAML::Key << "after" << YAML::Value << playback::to_string(raw.cycles.after)
        << YAML::Key << "before_count" << YAML::Value << raw.cycles.before_count << YAML::Key << "after_count" << YAML::Value
        << raw.cycles.after_count << YAML::EndMap;
    y << YAML::Key << "keys" << YAML::Value;
  }
  y << YAML::BeginSeq;
  for (std::size_t i = 0; i < raw.keys.size(); ++i) write_key(y, raw.keys[i], i > 0 ? &raw.keys[i - 1] : nullptr);
  y << YAML::EndSeq;
  if (long_form) y << YAML::EndMap;
}

/// The clips as a map of name to {duration, mode, tracks}.
void write_clips(YAML::Emitter& y, const std::vector<playback::Clip>& clips) {
  y << YAML::Key << "clips" << YAML::Value << YAML::BeginMap;
  for (const playback::Clip& clip : clips) {
    y << YAML::Key << clip.name << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "duration" << YAML::Value << clip.duration;
    y << YAML::Key << "mode" << YAML::Value << playback::to_string(clip.mode);
    y << YAML::Key << "tracks" << YAML::Value << YAML::BeginMap;
    for (const playback::Track& track : clip.tracks) {
      y << YAML::Key << track.channel << YAML::Value;
      write_curve(y, track.raw);
    }
    y << YAML::EndMap << YAML::EndMap;
  }
  y << YAML::EndMap;
}

void write_vector(YAML::Emitter& y, const Eigen::Vector3d& v) { y << YAML::Flow << std::vector<double>{v.x(), v.y(), v.z()}; }

void write_path(YAML::Emitter& y, const playback::PathSpec& path) {
  y << YAML::BeginMap << YAML::Key << "points" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    const auto left = path.left.empty() ? std::nullopt : path.left[i];
    const auto right = path.right.empty() ? std::nullopt : path.right[i];
    if (!left && !right) {
      write_vector(y, path.points[i]);
      continue;
    }
    y << YAML::BeginMap << YAML::Key << "at" << YAML::Value;
    write_vector(y, path.points[i]);
    if (left) {
      y << YAML::Key << "left" << YAML::Value;
      write_vector(y, *left);
    }
    if (right) {
      y << YAML::Key << "right" << YAML::Value;
      write_vector(y, *right);
    }
    y << YAML::EndMap;
  }
  y << YAML::EndSeq << YAML::Key << "spline" << YAML::Value << playback::to_string(path.spline);
  if (path.spline == playback::PathSpline::cardinal || path.spline == playback::PathSpline::kochanek_bartels)
    y << YAML::Key << "tension" << YAML::Value << path.tension;
  if (path.spline == playback::PathSpline::kochanek_bartels)
    y << YAML::Key << "continuity" << YAML::Value << path.continuity << YAML::Key << "bias" << YAML::Value << path.bias;
  y << YAML::Key << "from" << YAML::Value << path.from << YAML::Key << "to" << YAML::Value << path.to;
  const playback::DistanceTime& speed = path.speed;
  y << YAML::Key << "speed" << YAML::Value;
  if (speed.shape() == playback::DistanceTimeShape::user) {
    write_curve(y, speed.user_keys());
  } else if (speed.shape() == playback::DistanceTimeShape::sine_constant_middle ||
             speed.shape() == playback::DistanceTimeShape::parabolic) {
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "shape" << YAML::Value << playback::to_string(speed.shape()) << YAML::Key
      << "k1" << YAML::Value << speed.k1() << YAML::Key << "k2" << YAML::Value << speed.k2() << YAML::EndMap;
  } else {
    y << playback::to_string(speed.shape());
  }
  switch (path.orientation) {
    case playback::PathOrientation::none: break;
    case playback::PathOrientation::frenet: y << YAML::Key << "orient" << YAML::Value << "frenet"; break;
    case playback::PathOrientation::tangent:
      y << YAML::Key << "orient" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "along" << YAML::Value
        << "tangent" << YAML::Key << "up" << YAML::Value;
      write_vector(y, path.up);
      y << YAML::EndMap;
      break;
    case playback::PathOrientation::look_at:
      y << YAML::Key << "orient" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "look_at" << YAML::Value;
      write_vector(y, path.look_at);
      y << YAML::Key << "up" << YAML::Value;
      write_vector(y, path.up);
      y << YAML::EndMap;
      break;
  }
  y << YAML::EndMap;
}

/// A behaviour layer's span and seed, then its generators as they were read.
void write_behaviour(YAML::Emitter& y, const playback::LayerBehaviour& b) {
  const YAML::Node* text = detail::behaviour_text(b);
  if (!text)
    throw InputError(b.where, "a behaviour not read from a show file cannot be written; expected one from load_show_file");
  y << YAML::Key << "behaviour" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "seed" << YAML::Value << b.seed << YAML::Key << "from" << YAML::Value << b.from << YAML::Key << "to"
    << YAML::Value << b.to << YAML::Key << "fade_in" << YAML::Value << b.fade_in << YAML::Key << "fade_out" << YAML::Value
    << b.fade_out;
  for (const char* g : detail::kBehaviourGenerators)
    if ((*text)[g]) y << YAML::Key << g << YAML::Value << (*text)[g];
  y << YAML::EndMap;
}

/// The layers, bottom first; every placement field is written, the end resolved.
void write_layers(YAML::Emitter& y, const playback::Show& show) {
  y << YAML::Key << "layers" << YAML::Value << YAML::BeginSeq;
  for (const playback::Layer& layer : show.layers) {
    y << YAML::BeginMap;
    y << YAML::Key << "name" << YAML::Value << layer.name;
    y << YAML::Key << "blend" << YAML::Value << playback::to_string(layer.blend);
    y << YAML::Key << "weight" << YAML::Value << layer.weight;
    if (!layer.mask.empty()) {
      y << YAML::Key << "channels" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const playback::MaskChannel& m : layer.mask) y << m.channel;
      y << YAML::EndSeq;
    }
    if (layer.behaviour) {
      write_behaviour(y, *layer.behaviour);
      y << YAML::EndMap;
      continue;
    }
    y << YAML::Key << "clips" << YAML::Value << YAML::BeginSeq;
    for (const playback::Placement& p : layer.placements)
      y << YAML::Flow << YAML::BeginMap << YAML::Key << "clip" << YAML::Value << show.clips[p.clip].name << YAML::Key << "start"
        << YAML::Value << p.start << YAML::Key << "end" << YAML::Value << p.end << YAML::Key << "speed" << YAML::Value << p.speed
        << YAML::Key << "offset" << YAML::Value << p.offset << YAML::Key << "reverse" << YAML::Value << p.reverse << YAML::Key
        << "fade_in" << YAML::Value << p.fade_in << YAML::Key << "fade_out" << YAML::Value << p.fade_out << YAML::EndMap;
    y << YAML::EndSeq << YAML::EndMap;
  }
  y << YAML::EndSeq;
}

void write_orientation_keys(YAML::Emitter& y, const playback::OrientationKeysSpec& spec) {
  const bool any_euler = std::any_of(spec.keys.begin(), spec.keys.end(), [](const auto& k) { return !k.quaternion; });
  y << YAML::BeginMap;
  if (any_euler) y << YAML::Key << "order" << YAML::Value << playback::to_string(spec.order);
  y << YAML::Key << "interpolation" << YAML::Value << playback::to_string(spec.interpolation);
  y << YAML::Key << "keys" << YAML::Value << YAML::BeginSeq;
  for (const playback::OrientationKeySpec& k : spec.keys) {
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "time" << YAML::Value << k.time;
    if (k.quaternion) {
      y << YAML::Key << "quaternion" << YAML::Value << YAML::Flow
        << std::vector<double>{k.quaternion->w(), k.quaternion->x(), k.quaternion->y(), k.quaternion->z()};
    } else {
      y << YAML::Key << "euler" << YAML::Value;
      write_vector(y, k.euler);
    }
    y << YAML::EndMap;
  }
  y << YAML::EndSeq << YAML::EndMap;
}

/// An OSC cue argument as the reader types it back: a whole number is an int, a float keeps a
/// decimal point, a string is quoted.
void write_cue_argument(YAML::Emitter& y, const playback::CueArgument& a) {
  if (a.type == 'i') {
    y << static_cast<long long>(a.number);
  } else if (a.type == 'f') {
    std::string text;
    append_round_trip(text, a.number);
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
    y << text;
  } else {
    y << YAML::DoubleQuoted << a.text;
  }
}

/// The OSC cues; digital cues are written as the step tracks the reader made of them.
void write_osc_cues(YAML::Emitter& y, const std::vector<playback::Cue>& cues) {
  y << YAML::Key << "cues" << YAML::Value << YAML::BeginSeq;
  for (const playback::Cue& cue : cues) {
    if (!cue.is_osc()) continue;
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "time" << YAML::Value << cue.time << YAML::Key << "osc" << YAML::Value
      << YAML::Flow << YAML::BeginMap << YAML::Key << "to" << YAML::Value << cue.osc_host + ":" + std::to_string(cue.osc_port)
      << YAML::Key << "address" << YAML::Value << cue.osc_address;
    if (!cue.osc_arguments.empty()) {
      y << YAML::Key << "args" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const playback::CueArgument& a : cue.osc_arguments) write_cue_argument(y, a);
      y << YAML::EndSeq;
    }
    y << YAML::EndMap << YAML::EndMap;
  }
  y << YAML::EndSeq;
}

}  // namespace

std::string show_text(const playback::Show& show, const std::string& comment) {
  YAML::Emitter y;
  y.SetDoublePrecision(kDoublePrecision);
  y << YAML::BeginMap;
  y << YAML::Key << "name" << YAML::Value << show.name;
  y << YAML::Key << "duration" << YAML::Value << show.duration;
  y << YAML::Key << "loop" << YAML::Value << show.loop;
  y << YAML::Key << "tracks" << YAML::Value << YAML::BeginMap;
  for (const playback::Track& track : show.tracks) {
    y << YAML::Key << track.channel << YAML::Value;
    write_curve(y, track.raw);
  }
  y << YAML::EndMap;
  if (!show.targets.empty()) {
    y << YAML::Key << "targets" << YAML::Value << YAML::BeginMap;
    for (const playback::TargetTrack& target : show.targets) {
      y << YAML::Key << target.effector << YAML::Value << YAML::BeginMap;
      if (target.kind == playback::TargetKind::aim)
        y << YAML::Key << "aim" << YAML::Value << YAML::Flow
          << std::vector<double>{target.aim_axis[0], target.aim_axis[1], target.aim_axis[2]};
      const char* axes[3] = {"x", "y", "z"};
      const char* angles[3] = {"roll", "pitch", "yaw"};
      if (target.path) {
        y << YAML::Key << "path" << YAML::Value;
        write_path(y, target.path->spec());
      }
      if (target.orientation_keys) {
        y << YAML::Key << "orientation_keys" << YAML::Value;
        write_orientation_keys(y, target.orientation_keys->spec());
      }
      for (std::size_t i = 0; i < 3 && target.has_point() && !target.path; ++i) {
        y << YAML::Key << axes[i] << YAML::Value;
        write_curve(y, target.raw[i]);
      }
      const bool orientation_curves =
          target.has_orientation() && !target.orientation_keys && !(target.path && target.path->orients());
      for (std::size_t i = 0; i < 3 && orientation_curves; ++i) {
        y << YAML::Key << angles[i] << YAML::Value;
        write_curve(y, target.raw_rpy[i]);
      }
      y << YAML::EndMap;
    }
    y << YAML::EndMap;
  }
  if (!show.clips.empty()) write_clips(y, show.clips);
  if (!show.layers.empty()) write_layers(y, show);
  if (std::any_of(show.cues.begin(), show.cues.end(), [](const playback::Cue& c) { return c.is_osc(); }))
    write_osc_cues(y, show.cues);
  if (!show.markers.empty()) {
    y << YAML::Key << "markers" << YAML::Value << YAML::BeginSeq;
    for (const playback::Marker& m : show.markers)
      y << YAML::Flow << YAML::BeginMap << YAML::Key << "time" << YAML::Value << m.time << YAML::Key << "name" << YAML::Value
        << YAML::DoubleQuoted << m.name << YAML::EndMap;
    y << YAML::EndSeq;
  }
  y << YAML::EndMap;
  return "# " + comment + '\n' + y.c_str() + '\n';
}

namespace {

/// A node of the writer's YAML as JSON, scalars resolved as YAML's core schema does: a plain
/// number is a number, plain true and false are booleans, anything else (a quoted scalar
/// included) is a string.
nlohmann::json to_json(const YAML::Node& node) {
  if (node.IsMap()) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& entry : node) object[entry.first.Scalar()] = to_json(entry.second);
    return object;
  }
  if (node.IsSequence()) {
    nlohmann::json array = nlohmann::json::array();
    for (const auto& item : node) array.push_back(to_json(item));
    return array;
  }
  if (!node.IsScalar()) return nullptr;
  const std::string& text = node.Scalar();
  if (node.Tag() == "?") {  // plain, not quoted
    if (text == "true" || text == "false") return text == "true";
    char* end = nullptr;
    errno = 0;
    const long long whole = std::strtoll(text.c_str(), &end, 10);
    if (!text.empty() && *end == '\0' && errno == 0) return whole;
    const double x = std::strtod(text.c_str(), &end);
    if (!text.empty() && *end == '\0' && std::isfinite(x)) return x;
  }
  return text;
}

}  // namespace

std::string show_json(const playback::Show& show) {
  // One description of the file's fields: the writer's own text, read back as a tree.
  return to_json(YAML::Load(show_text(show, "json"))).dump();
}

std::string keys_json(const playback::RawCurve& raw, std::size_t from, std::size_t count) {
  YAML::Emitter y;
  y.SetDoublePrecision(kDoublePrecision);
  y << YAML::BeginSeq;
  for (std::size_t i = from; i < from + count; ++i) write_key(y, raw.keys[i], i > 0 ? &raw.keys[i - 1] : nullptr);
  y << YAML::EndSeq;
  return to_json(YAML::Load(y.c_str())).dump();
}

void write_show_file(const std::string& path, const playback::Show& show, const std::string& comment) {
  const std::string text = show_text(show, comment);
  std::ofstream file(path);
  file << text;
  if (!file) throw InputError({path, 0, 0}, "cannot write the show file; expected a writable path");
}

}  // namespace avar::config
