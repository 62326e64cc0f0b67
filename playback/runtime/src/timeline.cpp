#include "avar/playback/runtime/timeline.hpp"

#include <algorithm>

#include "avar/playback/runtime/idle_generator.hpp"

namespace avar::playback {

std::optional<Blend> blend_from_name(std::string_view name) {
  if (name == "override") return Blend::override;
  if (name == "additive") return Blend::additive;
  return std::nullopt;
}

const char* to_string(Blend blend) { return blend == Blend::additive ? "additive" : "override"; }

double smoothstep(double x) noexcept {
  if (!(x > 0)) return 0;
  if (x >= 1) return 1;
  return x * x * (3 - 2 * x);
}

double span_weight(double t, double start, double end, double fade_in, double fade_out) noexcept {
  if (!(t >= start && t <= end)) return 0;
  double w = 1;
  if (fade_in > 0) w *= smoothstep((t - start) / fade_in);
  if (fade_out > 0) w *= smoothstep((end - t) / fade_out);
  return w;
}

double Placement::weight(double t) const noexcept { return span_weight(t, start, end, fade_in, fade_out); }

double LayerBehaviour::weight(double t) const noexcept { return span_weight(t, from, to, fade_in, fade_out); }

double Placement::clip_time(const Clip& placed, double t) const noexcept {
  const double local = placed.local_time(offset + (t - start) * speed);
  return reverse ? placed.duration - local : local;
}

bool Layer::touches(std::string_view channel) const noexcept {
  return mask.empty() || std::any_of(mask.begin(), mask.end(), [&](const MaskChannel& m) { return m.channel == channel; });
}

std::vector<std::string> behaviour_channels(const Layer& layer) {
  std::vector<std::string> names;
  if (!layer.behaviour || !layer.behaviour->bound()) return names;
  const LayerBehaviour& b = *layer.behaviour;
  const IdleGenerator generators(b.idle, 0);
  for (std::size_t c = 0; c < b.channels.size() && c < generators.drives().size(); ++c)
    if (generators.drives()[c] && layer.touches(b.channels[c])) names.push_back(b.channels[c]);
  return names;
}

}  // namespace avar::playback
