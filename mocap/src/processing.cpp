#include "avar/mocap/processing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "avar/core/format.hpp"

namespace avar::mocap {
namespace {

/// More frames than this is refused as a likely mistake.
constexpr double kProcessingMaxFrames = 10'000'000;

/// A copy of everything but the frames.
SkeletonAnimation processing_shell(const SkeletonAnimation& a, double frame_time) {
  SkeletonAnimation out;
  out.source = a.source;
  out.joints = a.joints;
  out.channels = a.channels;
  out.frame_time = frame_time;
  return out;
}

/// Frames at start + i * step, i = 0 .. while <= end (evaluate()).
void sample_frames(const SkeletonAnimation& a, double start, double end, double step, SkeletonAnimation& out) {
  const double count = std::floor((end - start) / step + 1e-9) + 1;
  if (!(count <= kProcessingMaxFrames))
    throw std::invalid_argument(format_number(count) + " frames; expected at most " + format_number(kProcessingMaxFrames));
  out.frames.resize(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < out.frames.size(); ++i)
    evaluate(a, std::min(start + static_cast<double>(i) * step, end), out.frames[i]);
  align_hemispheres(out);
}

std::vector<double> processing_filter(const std::vector<double>& samples, playback::SmoothingMethod method, double rate,
                                      double cutoff) {
  return samples.size() < 2 ? samples : playback::smooth(samples, method, rate, cutoff);
}

}  // namespace

SkeletonAnimation resample(const SkeletonAnimation& a, double rate_hz) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0)
    throw std::invalid_argument("resampling rate " + format_number(rate_hz) + " Hz; expected more than 0");
  SkeletonAnimation out = processing_shell(a, 1.0 / rate_hz);
  sample_frames(a, 0, a.duration(), out.frame_time, out);
  return out;
}

SkeletonAnimation trim(const SkeletonAnimation& a, double from_s, double to_s) {
  if (!std::isfinite(from_s) || !std::isfinite(to_s) || from_s > to_s)
    throw std::invalid_argument("trim from " + format_number(from_s) + " s to " + format_number(to_s) +
                                " s; expected finite times, from before to");
  const double from = std::clamp(from_s, 0.0, a.duration());
  const double to = std::clamp(to_s, 0.0, a.duration());
  SkeletonAnimation out = processing_shell(a, a.frame_time);
  sample_frames(a, from, to, a.frame_time, out);
  return out;
}

SkeletonAnimation smooth(const SkeletonAnimation& a, playback::SmoothingMethod method, double cutoff_hz) {
  SkeletonAnimation out = a;
  align_hemispheres(out);
  if (method == playback::SmoothingMethod::none) return out;
  const double rate = 1.0 / a.frame_time;
  if (!(cutoff_hz > 0 && cutoff_hz < rate / 2))
    throw std::invalid_argument("smoothing cutoff " + format_number(cutoff_hz) + " Hz; expected more than 0 and below " +
                                format_number(rate / 2) + " Hz (half the frame rate)");
  const std::size_t frames = out.frames.size();
  std::vector<double> samples(frames);
  for (std::size_t j = 0; j < out.joints.size(); ++j) {
    for (int k = 0; k < 3; ++k) {
      for (std::size_t f = 0; f < frames; ++f) samples[f] = out.frames[f].translation[j][k];
      const std::vector<double> t = processing_filter(samples, method, rate, cutoff_hz);
      for (std::size_t f = 0; f < frames; ++f) samples[f] = out.frames[f].scale[j][k];
      const std::vector<double> s = processing_filter(samples, method, rate, cutoff_hz);
      for (std::size_t f = 0; f < frames; ++f) {
        out.frames[f].translation[j][k] = t[f];
        out.frames[f].scale[j][k] = s[f];
      }
    }
    for (int k = 0; k < 4; ++k) {
      for (std::size_t f = 0; f < frames; ++f) samples[f] = out.frames[f].rotation[j].coeffs()[k];
      const std::vector<double> q = processing_filter(samples, method, rate, cutoff_hz);
      for (std::size_t f = 0; f < frames; ++f) out.frames[f].rotation[j].coeffs()[k] = q[f];
    }
    for (std::size_t f = 0; f < frames; ++f) {
      Eigen::Quaterniond& q = out.frames[f].rotation[j];
      // Aligned unit quaternions average to a non-zero one; a zero would mean no motion to keep.
      q = q.norm() > 1e-12 ? q.normalized() : a.frames[f].rotation[j];
    }
  }
  align_hemispheres(out);
  return out;
}

double pose_distance(const SkeletonAnimation& a, std::size_t first, std::size_t second) {
  const Pose& p = a.frames.at(first);
  const Pose& q = a.frames.at(second);
  double sum = 0;
  for (std::size_t j = 0; j < p.rotation.size(); ++j) {
    const double angle = p.rotation[j].angularDistance(q.rotation[j]);
    sum += angle * angle;
  }
  return p.rotation.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(p.rotation.size()));
}

LoopMatch find_loop(const SkeletonAnimation& a, double min_length_s) {
  if (!std::isfinite(min_length_s) || min_length_s < 0)
    throw std::invalid_argument("loop length " + format_number(min_length_s) + " s; expected 0 or more");
  const auto gap = static_cast<std::size_t>(std::ceil(min_length_s / a.frame_time - 1e-9));
  const std::size_t min_gap = std::max<std::size_t>(gap, 1);
  if (a.frames.size() <= min_gap)
    throw std::invalid_argument("no two frames are " + format_number(min_length_s) + " s apart in " +
                                format_number(a.duration()) + " s of animation");
  LoopMatch best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + min_gap < a.frames.size(); ++i)
    for (std::size_t k = a.frames.size(); k-- > i + min_gap;) {
      const double d = pose_distance(a, i, k);
      if (d < best.distance) best = LoopMatch{i, k, d};
    }
  return best;
}

}  // namespace avar::mocap
