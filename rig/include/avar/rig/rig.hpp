#pragma once
// The rig: what a figure is made of, as loaded from a rig file. Names are resolved to dense
// indices once at load; everything downstream uses indices. Each link's protocol settings are
// parsed once into typed options (link_options.hpp) by the protocol's schema
// (protocol_schema.hpp); this is data only, no driver or device.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "avar/core/index.hpp"
#include "avar/core/input_error.hpp"
#include "avar/core/scalar_value.hpp"
#include "avar/firmware_iface/gpio_chip.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/kinematics/model.hpp"
#include "avar/kinematics/urdf_visuals.hpp"
#include "avar/rig/link_options.hpp"

namespace avar::rig {

/// Index into Rig::channels.
using ChannelIndex = Index<struct ChannelTag>;
/// Index into Rig::links.
using LinkIndex = Index<struct LinkTag>;

/// How a channel moves.
enum class ChannelKind {
  analog,   ///< any value in [min, max], reached within the motion limits
  digital,  ///< off (min) or on (max): a relay, valve or LED switches at once, no motion limits
};

const char* to_string(ChannelKind k) noexcept;

/// One degree of freedom the show animates (jaw, neck_pan...), in its own unit.
struct ChannelSpec {
  std::string name;
  std::string unit;  ///< free text: deg, mm, % ...
  /// digital: min 0, max 1, every command is 0 or 1 (a value at or above the middle of the range
  /// is on), so a step key switches on its tick; the motion limits below are infinite and the
  /// soft start, soft stop and fail-safe moves switch it at once.
  ChannelKind kind = ChannelKind::analog;
  double min = 0;               ///< hard lower limit (channel units); no command goes below
  double max = 1;               ///< hard upper limit (channel units), > min
  double rest = 0;              ///< rest pose, inside [min, max]: soft stop and faults go here
  double max_velocity = 0;      ///< limiter: largest speed commanded (units/s), > 0
  double max_acceleration = 0;  ///< limiter: units/s², > 0
  double max_jerk = 0;          ///< limiter: units/s³, > 0
  double soft_margin = 0;       ///< targets stay this far inside [min, max] (units), >= 0
  double ramp_velocity = 0;     ///< peak speed of soft start and soft stop (units/s), > 0
  /// With position feedback: a commanded-vs-measured difference beyond this is a fault
  /// (channel units); 0 = not checked.
  double tracking_tolerance = 0;
  SourceLocation where;

  bool digital() const noexcept { return kind == ChannelKind::digital; }
};

/// One setting of a link's protocol block (`maestro: {model: mini12}`): its key, where the key
/// stands, and its value as written.
struct LinkSetting {
  std::string key;
  SourceLocation key_where;
  ScalarValue value;
};

/// A link's protocol settings as written: what a reader hands the protocol's schema to parse
/// (ProtocolSchema::parse); not kept in the rig.
struct LinkSettings {
  std::vector<LinkSetting> entries;  ///< in file order
  SourceLocation where;              ///< the settings block
  std::string what;                  ///< names the block in messages: "the maestro settings of link 'head'"

  const ScalarValue* find(std::string_view key) const;
  /// Fails at the first key not in `allowed`, naming the block and the keys it takes.
  void expect_only_keys(std::span<const std::string_view> allowed) const;
  void expect_only_keys(std::initializer_list<std::string_view> allowed) const {
    expect_only_keys(std::span<const std::string_view>(allowed.begin(), allowed.size()));
  }
};

/// The alternative T of `options`, or T's defaults while it holds none.
template <class T, class Variant>
const T& options_or_defaults(const Variant& options) {
  static const T defaults{};
  if (std::holds_alternative<std::monostate>(options)) return defaults;
  return std::get<T>(options);
}

/// One physical connection. port "sim" means: a simulated device on a pseudo-terminal.
struct LinkSpec {
  std::string name;
  std::string protocol;  ///< a protocol's name in the registry: maestro, dynamixel, feetech...
  std::string port;      ///< "" for a device found otherwise (a Maestro on USB by its serial number)
  int baud = 0;
  double watchdog_s = 0.25;  ///< in real time: a link that completes no send for this long faults
  LinkOptions options;       ///< the protocol's settings, parsed (the alternative of `protocol`)
  SourceLocation where;

  bool simulated() const { return port == "sim"; }
  /// The parsed settings of a link of protocol T; T's defaults for a link built without
  /// options (not read from a file); std::bad_variant_access for another protocol's.
  template <class T>
  const T& options_as() const {
    return options_or_defaults<T>(options);
  }
};

/// What an actuator does when the controller faults.
enum class Failsafe {
  hold,     ///< keep the last command
  rest,     ///< ease to the channel's rest pose (within the limits)
  release,  ///< stop driving it (hobby servo: no pulses; smart servo: torque off)
};

const char* to_string(Failsafe f) noexcept;

/// One motor or servo, driving one channel, on one link.
struct ActuatorSpec {
  ChannelIndex channel;
  LinkIndex link;
  /// Where the actuator is on its link: Maestro / SSC-32 channel, servo ID, or DMX start address.
  int device_channel = 0;
  SourceLocation address_where;  ///< where the address (device_channel, id, address, node, line) stands
  bool fine = false;             ///< DMX: 16-bit (coarse at the address, fine at the next slot)
  firmware_iface::LinearCalibration calibration;
  std::optional<double> speed_limit;         ///< enforced by the device, channel units/s
  std::optional<double> acceleration_limit;  ///< enforced by the device, channel units/s²
  Failsafe failsafe = Failsafe::rest;
  /// Its own options, parsed: a drive's on a bus of drives, a GPIO line's; monostate elsewhere.
  ActuatorOptions options;
  /// On a bus of drives: the drive protocol (odrive, cia402, mit); empty elsewhere.
  std::string drive;
  SourceLocation where;

  /// Its parsed options of kind T, as LinkSpec::options_as.
  template <class T>
  const T& options_as() const {
    return options_or_defaults<T>(options);
  }
};

/// A kinematic joint driven by a channel: joint value (rad or m) = (channel value - offset) * scale.
struct JointBinding {
  std::size_t q_index = 0;  ///< the joint's entry in the model's q
  std::size_t channel = 0;  ///< index into Rig::channels
  double scale = 1;         ///< joint units (rad, m) per channel unit
  double offset = 0;        ///< channel value at joint zero
  double to_joint(double channel_value) const noexcept { return (channel_value - offset) * scale; }
  double to_channel(double joint_value) const noexcept { return joint_value / scale + offset; }
};

/// The figure as a linkage, for inverse kinematics: the joint tree with named effectors, and
/// which channel drives each movable joint. Joint limits are the channels' limits.
struct RigKinematics {
  kinematics::Model model;
  std::vector<JointBinding> bindings;  ///< one per movable joint, in q order
  SourceLocation where;
  /// What the figure looks like, for previews (a URDF's <visual> elements); empty: draw the
  /// joint tree with simple shapes.
  std::vector<kinematics::LinkVisual> visuals;
};

/// Indices into RigKinematics::bindings of the joints that move an effector (every movable joint
/// between it and the base).
std::vector<std::size_t> bindings_moving(const RigKinematics& kinematics, std::size_t effector);

/// The actuators of a rig that sit on one link: iterate it with a range for. (Hand-written:
/// clang 14, which the lint runs, cannot read libstdc++ 12's std::views::filter.)
class ActuatorsOnLink {
 public:
  class iterator {
   public:
    iterator(const std::vector<ActuatorSpec>* all, std::size_t at, LinkIndex link) : all_(all), at_(at), link_(link) { skip(); }
    const ActuatorSpec& operator*() const { return (*all_)[at_]; }
    iterator& operator++() {
      ++at_;
      skip();
      return *this;
    }
    bool operator==(const iterator& other) const { return at_ == other.at_; }

   private:
    void skip() {
      while (at_ < all_->size() && (*all_)[at_].link != link_) ++at_;
    }
    const std::vector<ActuatorSpec>* all_;
    std::size_t at_;
    LinkIndex link_;
  };

  ActuatorsOnLink(const std::vector<ActuatorSpec>* all, LinkIndex link) : all_(all), link_(link) {}
  iterator begin() const { return {all_, 0, link_}; }
  iterator end() const { return {all_, all_->size(), link_}; }

 private:
  const std::vector<ActuatorSpec>* all_;
  LinkIndex link_;
};

/// What a digital input does.
enum class InputRole {
  estop,    ///< active: the e-stop (a fault source of the supervisor, latching FaultCause::estop)
  control,  ///< a named control (0 or 1) delivered to the live inputs' sink under the input's name
  start,    ///< a show start button: each debounced press is counted
};

const char* to_string(InputRole r) noexcept;

/// A digital input on a GPIO line (`digital_inputs:` in a rig file): an e-stop, a limit switch,
/// a start button.
struct DigitalInputSpec {
  std::string name;
  std::string chip;  ///< gpiochip0, a chip's label or path, or "sim" (a simulated chip)
  unsigned line = 0;
  bool active_low = false;  ///< the input is active (1) while the line is low
  firmware_iface::GpioBias bias = firmware_iface::GpioBias::as_is;
  double debounce_s = 0.01;  ///< a change counts once the line stayed put this long
  InputRole role = InputRole::control;
  SourceLocation where;

  bool simulated() const { return chip == "sim"; }
};

struct Rig {
  std::string name;
  std::string file;
  double rate_hz = 50;  ///< default tick rate
  std::vector<ChannelSpec> channels;
  std::vector<LinkSpec> links;
  std::vector<ActuatorSpec> actuators;
  std::optional<RigKinematics> kinematics;  ///< when the rig file has a kinematics section
  std::vector<DigitalInputSpec> digital_inputs;

  std::optional<std::size_t> find_channel(std::string_view wanted) const;
  std::optional<std::size_t> find_link(std::string_view wanted) const;
  const ChannelSpec& channel(ChannelIndex c) const { return channels[c.value]; }
  const LinkSpec& link(LinkIndex l) const { return links[l.value]; }
  /// The actuators on one link, in file order (the order drivers and simulated devices list
  /// them in). A view: no copy.
  ActuatorsOnLink actuators_on(LinkIndex l) const { return {&actuators, l}; }
  /// The channels' rest poses, as a frame.
  std::vector<double> rest_frame() const;
  /// Comma-separated channel names, for error messages.
  std::string channel_names() const;
};

}  // namespace avar::rig
