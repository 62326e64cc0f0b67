#pragma once
// Live puppeteering: named controls (from input devices, through a ControlMailbox) mapped onto
// channels and mixed over the show (ControlMixer). Each mapping is one mixer layer:
//  - absolute: the shaped control spans an output range of the channel (its limits unless
//    stated): bipolar -1..1 -> low..high with 0 at the middle, unipolar 0..1 -> low..high;
//  - relative: the shaped control is a speed (rate, channel units/s, at full deflection) that
//    moves the channel from where it was when the control took it, within the channel's limits.
// A mapping with a `hold` control is active only while that control reads 0.5 or more (a
// dead-man button). Besides the mappings, every channel has a direct control `channel/NAME`
// (OSC's /avar/channel/NAME), in channel units, above every mapping.
//
// A mapping may drive one axis of an inverse-kinematics target instead of a channel (a joystick
// steering a gaze point): its output is a coordinate of the effector's goal (metres, the rig's
// base frame) within the mapping's range, absolute or relative as above, mixed over the show's
// goal by a mixer of its own (LiveLayer::apply_targets); the joints follow through the IK and
// the limiter. An effector no target of the show moves ignores it.
//
// Construction allocates; apply() is real-time safe (the mixer's, the shaping's and the
// mailbox's reads only). One loop thread calls apply(); input threads post to sink().

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "avar/control/control_mailbox.hpp"
#include "avar/control/control_mixer.hpp"
#include "avar/control/control_shape.hpp"
#include "avar/control/live_layer.hpp"

namespace avar::control {

enum class MappingMode { absolute, relative };
enum class MappingOutput { channel, target };

struct ControlMapping {
  std::string control;      ///< as input devices name it: "x", "ch1.cc7", "jaw"
  std::size_t channel = 0;  ///< index into the frame (output channel)
  MappingOutput output = MappingOutput::channel;
  std::size_t effector = 0;  ///< output target: index into the effectors given to LiveInputs
  std::size_t axis = 0;      ///< output target: 0 x, 1 y, 2 z
  MappingMode mode = MappingMode::absolute;
  ControlShape shape;
  double low = 0, high = 1;  ///< absolute: the output range, channel units (target: metres, and a relative one's bounds)
  double rate = 0;           ///< relative: channel units/s at full deflection (target: m/s)
  std::string hold;          ///< a control that must read >= 0.5 for the mapping to act; empty: none
  int priority = 10;
  Blend blend = Blend::override;
  double crossfade_s = 0.3;
  double timeout_s = 0;  ///< release after this long without a message (or, relative, deflection); 0 = never
};

/// A channel's name and limits, as the mappings need them.
struct LiveChannel {
  std::string name;
  double min = 0, max = 1;
};

/// The direct channel controls' layer: above mappings, a short crossfade, released after 2 s of
/// silence.
inline constexpr int kDirectPriority = 1000;
inline constexpr double kDirectCrossfadeS = 0.2;
inline constexpr double kDirectTimeoutS = 2.0;

class LiveInputs final : public LiveLayer {
 public:
  /// `effectors`: the names of the rig's kinematic effectors, in the model's order (what target
  /// mappings index). std::invalid_argument for a mapping whose channel, effector or axis is out
  /// of range, or a target mapping whose range is not finite.
  LiveInputs(std::vector<LiveChannel> channels, std::vector<ControlMapping> mappings, std::vector<std::string> effectors = {});

  /// Where input devices post (borrowed by them; lives as long as this object).
  ControlMailbox& sink() noexcept { return mailbox_; }
  const ControlMailbox& mailbox() const noexcept { return mailbox_; }

  void apply(double now_s, std::span<double> frame) noexcept override;
  void apply_targets(double now_s, std::span<double> points) noexcept override;

  /// Every control's latest raw value as the last apply() read it (NaN: never moved), indexed
  /// as mailbox(); for traces. Loop thread.
  std::span<const double> control_values() const noexcept { return values_; }
  const ControlMixer& mixer() const noexcept { return mixer_; }
  /// The target mappings' mixer: layer k is the k-th target mapping; "channel" 3e + a is axis a
  /// of effector e.
  const ControlMixer& target_mixer() const noexcept { return target_mixer_; }
  /// Per channel: whether any live layer has had a weight above 0 on it so far (a take's channels).
  std::span<const char> touched() const noexcept { return touched_; }
  /// Per effector: whether a target mapping has had a weight above 0 on its goal so far (a take's
  /// joints: the channels that move that effector).
  std::span<const char> targets_touched() const noexcept { return targets_touched_; }
  const std::vector<ControlMapping>& mappings() const noexcept { return mappings_; }
  /// The newest arrival time (CLOCK_MONOTONIC ns) among the messages the last apply() took
  /// for the first time; 0 when it took none. For latency measurement.
  std::int64_t newest_taken_ns() const noexcept { return newest_taken_ns_; }

 private:
  struct MappingState {
    std::size_t layer = 0;  ///< in mixer_ or, for a target mapping, target_mixer_
    std::size_t slot = 0;
    std::size_t hold_slot = 0;  ///< == mailbox size when none
    std::uint64_t seen = 0;
    double smoothed = 0;
    double position = 0;  ///< relative: where the channel is driven to
    bool started = false;
  };
  /// Reads mapping i's control and sets its layer in `mixer`; `last`: that mixer's last output,
  /// where a relative mapping takes over from.
  void drive(std::size_t i, double now_s, double dt, ControlMixer& mixer, std::span<const double> last) noexcept;

  std::vector<LiveChannel> channels_;
  std::vector<ControlMapping> mappings_;
  std::vector<std::string> effectors_;
  ControlMailbox mailbox_;
  ControlMixer mixer_;
  ControlMixer target_mixer_;
  std::vector<MappingState> state_;
  std::vector<std::size_t> direct_slot_;  ///< per channel
  std::vector<std::uint64_t> direct_seen_;
  std::vector<double> values_;
  std::vector<double> last_out_;  ///< the frame the last apply() produced
  std::vector<char> touched_;
  std::vector<char> targets_touched_;
  std::vector<double> last_points_;  ///< the goal points the last apply_targets() produced
  double last_now_ = 0, last_targets_now_ = 0;
  bool applied_ = false, targets_applied_ = false;
  std::int64_t newest_taken_ns_ = 0;
  std::int64_t taking_ns_ = 0;  ///< newest arrival taken since the last apply() (apply_targets() runs first)
};

}  // namespace avar::control
