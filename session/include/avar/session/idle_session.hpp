#pragma once
// Idle life in one run of play or idle: the rig's idle: section as a layer below the show
// (control::IdleLayer), stacked under the live inputs when there are any (control::LayerStack):
// e-stop/fault > puppeteer > show > idle.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>

#include "avar/control/idle_layer.hpp"
#include "avar/control/layer_stack.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"

namespace avar::session {

class IdleSession {
 public:
  /// Reads the idle: section of the rig's file. Throws InputError when it has none or it is
  /// wrong (naming file:line:col).
  IdleSession(const rig::Rig& rig, const playback::Show& show, std::uint64_t seed);

  /// The layer for ControllerOptions::live: idle at the bottom, `above` (live inputs; may be
  /// null) over it. Valid as long as this session.
  control::LiveLayer* layers(control::LiveLayer* above);
  /// Idle follows this controller's show clock (yields to the show while it plays).
  void watch(const control::Controller& controller) noexcept { idle_.watch(controller); }
  const control::IdleLayer& idle() const noexcept { return idle_; }
  std::uint64_t seed() const noexcept { return seed_; }
  /// One line for the summary: the seed, the blinks' and saccades' counts.
  void describe(std::ostream& out) const;

 private:
  std::uint64_t seed_;
  control::IdleLayer idle_;
  std::optional<control::LayerStack> stack_;
};

/// A seed for a run given none (from the system's entropy); printed so a run can be repeated.
std::uint64_t fresh_idle_seed();

}  // namespace avar::session
