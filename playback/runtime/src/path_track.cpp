#include "avar/playback/runtime/path_track.hpp"

#include <algorithm>
#include <cmath>

namespace avar::playback {
namespace {

constexpr const char* kSplineNames[] = {"linear", "catmull_rom", "cardinal", "kochanek_bartels", "bspline", "bezier"};

}  // namespace

std::optional<PathSpline> path_spline_from_name(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kSplineNames); ++i)
    if (name == kSplineNames[i]) return static_cast<PathSpline>(i);
  return std::nullopt;
}

const char* to_string(PathSpline spline) { return kSplineNames[static_cast<std::size_t>(spline)]; }

const char* path_spline_names() { return "linear, catmull_rom, cardinal, kochanek_bartels, bspline, bezier"; }

std::size_t PathTrack::locate(double& u) const noexcept {
  const double n = static_cast<double>(cubics_.size());
  u = std::clamp(u, 0.0, n);  // a NaN u stays NaN: the callers get it only from the table, which never gives one
  const std::size_t i = std::min(cubics_.size() - 1, static_cast<std::size_t>(std::max(0.0, std::floor(u))));
  u -= static_cast<double>(i);
  return i;
}

Eigen::Vector3d PathTrack::position_at(double u) const noexcept {
  const std::size_t i = locate(u);
  const Cubic& c = cubics_[i];
  return c[0] + u * (c[1] + u * (c[2] + u * c[3]));
}

Eigen::Vector3d PathTrack::derivative_at(double u) const noexcept {
  const std::size_t i = locate(u);
  const Cubic& c = cubics_[i];
  return c[1] + u * (2 * c[2] + u * 3 * c[3]);
}

Eigen::Vector3d PathTrack::second_derivative_at(double u) const noexcept {
  const std::size_t i = locate(u);
  const Cubic& c = cubics_[i];
  return 2 * c[2] + 6 * u * c[3];
}

PathSample PathTrack::sample(double t) const noexcept {
  PathSample out;
  const double total = length();
  out.distance = total * spec_.speed.distance((t - spec_.from) / (spec_.to - spec_.from));
  out.position = position_at(table_.parameter_at(out.distance));
  if (!frames_.empty()) {
    const double x = std::clamp(out.distance / total, 0.0, 1.0) * static_cast<double>(kFrameSamples);
    const std::size_t k = std::min(kFrameSamples - 1, static_cast<std::size_t>(x));
    out.orientation = frames_[k].slerp(x - static_cast<double>(k), frames_[k + 1]);
  }
  return out;
}

}  // namespace avar::playback
