#include "avar/config/mocap_bake.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>

#include "avar/config/show_behaviour.hpp"
#include "avar/config/retarget_map.hpp"
#include "avar/config/show_file.hpp"
#include "avar/core/format.hpp"
#include "avar/playback/offline/track_fit.hpp"
#include "avar/mocap/mocap_file.hpp"

namespace avar::config {
namespace {

using playback::fit_track;
using playback::max_fit_error;

/// Samples outside [min, max]: refused at the binding, or clamped (counted) with `clamp`.
std::size_t bake_keep_in_limits(const mocap::RetargetedMotion& motion, mocap::RetargetedMotion::Channel& channel,
                                const mocap::RotationBinding& binding, const rig::ChannelSpec& spec, bool clamp) {
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < channel.values.size(); ++i) {
    double& v = channel.values[i];
    if (v >= spec.min && v <= spec.max) continue;
    if (!clamp)
      throw InputError(binding.where, "channel '" + spec.name + "' reaches " + format_number(v) + " " + spec.unit + " at " +
                                          format_number(motion.times[i]) + " s, outside its limits [" + format_number(spec.min) +
                                          ", " + format_number(spec.max) +
                                          "]; expected this binding's scale, offset or reverse to keep it inside (or --clamp)");
    v = std::clamp(v, spec.min, spec.max);
    ++clamped;
  }
  return clamped;
}

}  // namespace

bool is_mocap_file(const std::string& path) {
  try {
    (void)mocap::mocap_format(path);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

mocap::SkeletonAnimation load_motion_file(const std::string& path, double sample_rate_hz) {
  mocap::MocapLoadOptions options;
  options.sample_rate_hz = sample_rate_hz;
  return mocap::load_mocap_file(path, options);
}

Baked bake_show(const mocap::SkeletonAnimation& animation, const mocap::RetargetMap& map, const rig::Rig& rig,
                const BakeSettings& settings, const std::string& name, std::ostream* progress) {
  const SourceLocation map_where{map.file, 0, 0};
  if (!(animation.duration() > 0))
    throw InputError({animation.source, 0, 0}, "the animation has " + std::to_string(animation.frame_count()) +
                                                   " frame(s) spanning no time; expected at least two frames to bake a show");
  const double rate = settings.sample_rate_hz > 0 ? settings.sample_rate_hz : 1 / animation.frame_time;
  if (progress) *progress << "retargeting " << animation.frame_count() << " frames at " << format_number(rate) << " Hz\n";
  Baked baked;
  baked.samples = mocap::retarget(animation, map, rate);
  const mocap::RetargetedMotion& m = baked.samples;
  baked.show.name = name;
  baked.show.duration = m.times.back();
  baked.show.where = map_where;
  const std::size_t fits = m.channels.size() + 3 * m.targets.size();
  std::size_t done = 0;
  for (auto& channel : baked.samples.channels) {
    const mocap::RotationBinding& b = map.rotations[channel.binding];
    const rig::ChannelSpec& spec = rig.channels[*rig.find_channel(channel.channel)];
    const std::size_t clamped = bake_keep_in_limits(m, channel, b, spec, settings.clamp);
    if (progress) *progress << "fitting " << ++done << "/" << fits << ": " << channel.channel << '\n';
    baked.show.tracks.push_back(
        fit_track(channel.channel, m.times, channel.values, settings.tolerance, settings.corner_angle_deg, b.where));
    baked.report.channels.push_back(
        {channel.channel, spec.unit, m.times.size(), baked.show.tracks.back().curve.key_count(), 0, clamped});
  }
  for (const auto& target : m.targets) {
    const mocap::PositionBinding& b = map.positions[target.binding];
    playback::TargetTrack track;
    track.effector = target.target;
    track.kind = playback::TargetKind::position;
    track.where = b.where;
    for (std::size_t a = 0; a < 3; ++a) {
      const std::string axis = target.target + "." + "xyz"[a];
      if (progress) *progress << "fitting " << ++done << "/" << fits << ": " << axis << '\n';
      const playback::Track fitted =
          fit_track(axis, m.times, target.xyz[a], settings.position_tolerance, settings.corner_angle_deg, b.where);
      track.raw[a] = fitted.raw;
      track.xyz[a] = fitted.curve;
      baked.report.channels.push_back({axis, "m", m.times.size(), fitted.curve.key_count(), 0, 0});
    }
    baked.show.targets.push_back(std::move(track));
  }
  measure_fit(baked.show, baked.samples, baked.report);
  return baked;
}

void measure_fit(const playback::Show& show, const mocap::RetargetedMotion& samples, BakeReport& report) {
  // By name: a show read back from its file may list its tracks and targets in another order.
  std::size_t entry = 0;
  for (const auto& channel : samples.channels) {
    const auto track =
        std::find_if(show.tracks.begin(), show.tracks.end(), [&](const auto& t) { return t.channel == channel.channel; });
    if (track != show.tracks.end()) report.channels[entry].max_error = max_fit_error(track->curve, samples.times, channel.values);
    ++entry;
  }
  for (const auto& target : samples.targets) {
    const auto found =
        std::find_if(show.targets.begin(), show.targets.end(), [&](const auto& t) { return t.effector == target.target; });
    for (std::size_t a = 0; a < 3; ++a, ++entry)
      if (found != show.targets.end())
        report.channels[entry].max_error = max_fit_error(found->xyz[a], samples.times, target.xyz[a]);
  }
}

playback::Show load_playable_show(const std::string& path, const std::optional<std::string>& map_path, const rig::Rig& rig) {
  if (!map_path) {
    if (is_mocap_file(path))
      throw InputError({path, 0, 0}, "found a motion-capture file; expected --map MAP.yaml to retarget it onto the rig");
    playback::Show show = config::load_show_file(path);
    config::bind_show_behaviour(show, rig);
    return show;
  }
  if (!is_mocap_file(path))
    throw InputError({path, 0, 0},
                     "--map retargets motion capture; expected a .bvh, .gltf or .glb file, found another kind of file");
  const mocap::RetargetMap map = config::load_retarget_map(*map_path, rig);
  const mocap::SkeletonAnimation animation = load_motion_file(path, 30);
  return bake_show(animation, map, rig, BakeSettings{}, std::filesystem::path(path).stem().string(), nullptr).show;
}

}  // namespace avar::config
