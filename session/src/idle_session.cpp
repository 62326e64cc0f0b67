#include "avar/session/idle_session.hpp"

#include <ostream>
#include <random>

#include "avar/config/idle_section.hpp"

namespace avar::session {
namespace {

playback::IdleSpec idle_spec_of(const rig::Rig& rig) {
  std::optional<playback::IdleSpec> spec = config::load_idle_section(rig, rig.file);
  if (!spec) throw InputError({rig.file, 1, 1}, "--idle needs an idle: section in the rig file (noise, blinks, gaze, breathing)");
  return std::move(*spec);
}

}  // namespace

IdleSession::IdleSession(const rig::Rig& rig, const playback::Show& show, std::uint64_t seed)
    : seed_(seed), idle_(idle_spec_of(rig), seed, control::show_drives(rig, show), rig.kinematics ? &*rig.kinematics : nullptr) {}

control::LiveLayer* IdleSession::layers(control::LiveLayer* above) {
  if (!above) return &idle_;
  stack_.emplace(std::vector<control::LiveLayer*>{&idle_, above});
  return &*stack_;
}

void IdleSession::describe(std::ostream& out) const {
  const playback::IdleGenerator& g = idle_.generator();
  out << "  idle: seed " << seed_ << " (repeat with --seed " << seed_ << ")";
  if (g.gaze()) out << ", " << g.gaze()->saccades() << " saccades";
  if (const control::GazeLookAt* look = idle_.look_at()) {
    const control::IkStats& s = look->stats();
    out << " (eyes aimed: " << s.converged << " converged, " << s.degraded << " out of reach, " << s.failed << " failed)";
  }
  out << '\n';
}

std::uint64_t fresh_idle_seed() {
  std::random_device entropy;
  return (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
}

}  // namespace avar::session
