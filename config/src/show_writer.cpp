#include "avar/config/show_writer.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::config {
namespace {

using playback::Interpolation;

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

}  // namespace

void write_show_file(const std::string& path, const playback::Show& show, const std::string& comment) {
  YAML::Emitter y;
  y.SetDoublePrecision(17);
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
      for (std::size_t i = 0; i < 3 && target.has_point(); ++i) {
        y << YAML::Key << axes[i] << YAML::Value;
        write_curve(y, target.raw[i]);
      }
      for (std::size_t i = 0; i < 3 && target.has_orientation(); ++i) {
        y << YAML::Key << angles[i] << YAML::Value;
        write_curve(y, target.raw_rpy[i]);
      }
      y << YAML::EndMap;
    }
    y << YAML::EndMap;
  }
  if (!show.clips.empty()) write_clips(y, show.clips);
  if (!show.layers.empty()) write_layers(y, show);
  y << YAML::EndMap;
  std::ofstream file(path);
  file << "# " << comment << '\n' << y.c_str() << '\n';
  if (!file) throw InputError({path, 0, 0}, "cannot write the show file; expected a writable path");
}

}  // namespace avar::config
