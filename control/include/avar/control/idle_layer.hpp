#pragma once
// Idle life as a live layer below the show (playback::IdleGenerator mixed by a ControlMixer, one
// override layer per channel idle drives). Where the show drives a channel and the show is
// playing, the show wins: idle's weight on that channel fades to 0 so that it is 0 when the
// show starts, and fades back in when the show (its last pass) ends. On channels the show does
// not drive, idle drives throughout, faded in when the run starts. The crossfades are the
// mixer's (eased, continuous in value and slope). Channels idle does not drive are untouched.
//
// Construction allocates; apply() is real-time safe (loop thread).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "avar/control/control_mixer.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/gaze_look_at.hpp"
#include "avar/control/live_layer.hpp"
#include "avar/playback/runtime/idle_generator.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"

namespace avar::control {

/// Per channel of the rig: 1 where the show moves it (its tracks, its clips' tracks, the
/// channels its behaviour layers move once bound to the rig (config::bind_show_behaviour), and
/// the joints its inverse-kinematics targets turn). A layer's mask does not add channels.
std::vector<char> show_drives(const rig::Rig& rig, const playback::Show& show);

class IdleLayer final : public LiveLayer {
 public:
  /// `show_drives`: per frame channel (spec.limits.size()), 1 where the show drives it. Without
  /// watch(), the show counts as never playing (idle drives every one of its channels).
  /// `kinematics` (copied; needed when the gaze is look-at, ignored otherwise) aims the eyes; they
  /// are solved with the figure posed as the frame under idle, and idle's own channels as idle
  /// puts them. Throws std::invalid_argument for look-at gaze without kinematics.
  IdleLayer(const playback::IdleSpec& spec, std::uint64_t seed, std::vector<char> show_drives,
            const rig::RigKinematics* kinematics = nullptr);

  /// Follows `controller`'s show clock (borrowed; outlives this layer): the show plays from
  /// show time 0 to Controller::show_end().
  void watch(const Controller& controller) noexcept { controller_ = &controller; }

  void apply(double now_s, std::span<double> frame) noexcept override;

  const playback::IdleGenerator& generator() const noexcept { return idle_; }
  const ControlMixer& mixer() const noexcept { return mixer_; }
  /// Look-at gaze's eye solver, when the gaze is look-at.
  const GazeLookAt* look_at() const noexcept { return look_at_.get(); }
  /// The eased weight idle had on `channel` at the last apply (0 where it does not drive it).
  double weight(std::size_t channel) const noexcept;

 private:
  bool show_playing() const noexcept;

  std::unique_ptr<GazeLookAt> look_at_;  ///< on the heap: the generator keeps its address
  playback::IdleGenerator idle_;
  std::vector<char> show_drives_;
  std::vector<std::size_t> channels_;  ///< mixer layer -> channel
  std::vector<std::size_t> layer_of_;  ///< channel -> mixer layer (or size of channels_)
  ControlMixer mixer_;
  std::vector<double> idle_frame_;
  const Controller* controller_ = nullptr;
};

}  // namespace avar::control
