#include "avar/playback/runtime/behaviour_player.hpp"

#include <cmath>

namespace avar::playback {

BehaviourPlayer::BehaviourPlayer(const IdleSpec& spec, std::uint64_t seed)
    : start_(spec, seed), stepped_(start_), probe_(start_), scratch_(spec.limits.size(), 0.0) {
  for (std::size_t c = 0; c < scratch_.size(); ++c) scratch_[c] = spec.limits[c].rest;
}

void BehaviourPlayer::sample(double tau_s, std::span<double> frame) noexcept {
  if (frame.size() != scratch_.size() || !std::isfinite(tau_s)) return;
  const double tau = tau_s > 0 ? tau_s : 0.0;
  const auto grid = static_cast<std::int64_t>(std::floor(tau / kBehaviourStep));
  if (grid < step_) {
    stepped_ = start_;
    step_ = -1;
    ++restarts_;
  }
  while (step_ < grid) {
    ++step_;
    ++steps_;
    stepped_.sample(static_cast<double>(step_) * kBehaviourStep, scratch_);
  }
  probe_ = stepped_;
  probe_.sample(tau, frame);
}

}  // namespace avar::playback
