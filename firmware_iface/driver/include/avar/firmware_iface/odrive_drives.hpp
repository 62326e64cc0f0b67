#pragma once
// ODrive axes on a CAN link, speaking CAN Simple (firmware 0.5.x; ../shared/protocols/odrive-cansimple.md).
// Each actuator is one axis (one node) in position control:
//
// - start(): per axis, Clear Errors, read the present position (RTR Get Encoder Estimates), Set
//   Controller Modes (position control, the actuator's input mode), Set Limits, Set Input Pos =
//   the present position (no jump), request CLOSED_LOOP_CONTROL and wait for a heartbeat that
//   shows it. A failure idles the axes already started and names the node and what its
//   heartbeat said.
// - each tick: Set Input Pos per driven axis (its channel through the calibration, saturated),
//   plus an RTR Get Encoder Estimates per driven axis when readback is rtr; a newly released axis
//   gets Set Axis Requested State IDLE once. Replies: heartbeats (axis error, state) and encoder
//   estimates (telemetry position). A driven axis whose heartbeat shows an axis error or a state
//   other than CLOSED_LOOP_CONTROL gets kDeviceFaultState (plus the DeviceFault bits of its
//   error); one whose heartbeat is missing for heartbeat_budget_ticks ticks in a row gets
//   kDeviceLost (DeviceWatch: device_watch.hpp).
// - release: Set Axis Requested State IDLE to every axis (the motors coast).
//
// Threads and real-time rules: as CanDrives (can_drives.hpp).

#include <atomic>
#include <chrono>
#include <limits>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/can_drives.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/firmware_iface/odrive_can_codec.hpp"

namespace avar::firmware_iface {

struct OdriveActuator {
  std::size_t channel = 0;        ///< rig channel index
  std::uint8_t node = 0;          ///< the axis's CAN node ID, 0..63
  LinearCalibration calibration;  ///< channel units -> motor turns
  double velocity_limit = 2;      ///< turns/s, sent with Set Limits (> 0)
  double current_limit = 10;      ///< A, sent with Set Limits (> 0)
  /// passthrough (the streamed positions as they come), pos_filter or trap_traj (smoothed on the
  /// drive; the filter's bandwidth and the trajectory limits are the drive's own configuration).
  odrive::InputMode input_mode = odrive::InputMode::passthrough;
};

enum class OdriveReadback {
  rtr,   ///< an RTR Get Encoder Estimates per axis every tick: position telemetry
  none,  ///< commands only (heartbeats still watched); estimates the drives send cyclically are used
};

struct OdriveDrivesConfig {
  std::vector<OdriveActuator> actuators;
  OdriveReadback readback = OdriveReadback::rtr;
  odrive::HeartbeatLayout heartbeat_layout = odrive::HeartbeatLayout::v0_5;
  /// Ticks in a row without a heartbeat that make an axis lost (its DeviceWatch budget). At least
  /// a few heartbeat periods: 30 ticks are 3 heartbeats (100 ms each) at 100 Hz.
  std::uint32_t heartbeat_budget_ticks = 30;
  /// start() and read_positions(): longest wait for an encoder estimate (transport clock).
  std::chrono::milliseconds reply_timeout{100};
  /// The control loop's tick (s). When set, every Set Input Pos carries the velocity of the
  /// commanded motion as its feed-forward ((this command - the last) / tick), so that the axis's
  /// own position loop does not lag a moving curve; 0: no feed-forward.
  double tick_period_s = 0;
  /// start(): longest wait for a heartbeat showing CLOSED_LOOP_CONTROL after the request
  /// (entering closed loop may take a while on some setups).
  std::chrono::milliseconds closed_loop_timeout{2000};
};

class OdriveDrives final : public CanDrives {
 public:
  /// Throws std::invalid_argument for a node out of range or used twice, a limit that is not a
  /// positive finite number, an input mode other than passthrough, pos_filter and trap_traj, or a
  /// zero heartbeat budget.
  explicit OdriveDrives(OdriveDrivesConfig config);

  const char* device_name() const noexcept override { return "ODrive"; }
  Status start(FrameTransport& bus) override;
  std::string start_problem() const override { return start_problem_; }
  Status read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) override;
  std::size_t max_tick_frames() const noexcept override;
  void encode_tick(std::span<const double> frame, CanOutbox& out) noexcept override;
  bool take(const CanFrame& frame) noexcept override;
  bool replies_complete() const noexcept override;
  Status settle() noexcept override;
  void encode_release(CanOutbox& out) noexcept override;
  std::string channel_problem(std::size_t channel) const override;
  std::uint64_t device_errors() const noexcept override { return device_errors_.load(std::memory_order_relaxed); }

  const OdriveDrivesConfig& config() const noexcept { return config_; }

 private:
  struct Axis {
    std::uint8_t node = 0;
    odrive::Heartbeat last_heartbeat;  ///< as of the latest heartbeat
    bool heartbeat_seen = false;       ///< ever, since start
    bool heartbeat_this_tick = false;
    DeviceWatch heartbeat;                                         ///< heartbeat silence, against the budget
    bool estimate_asked = false;                                   ///< this tick
    bool estimate_taken = false;                                   ///< this tick
    DeviceWatch estimates{kStopWaitingAfter};                      ///< lost: no longer waited for
    double last_turns = std::numeric_limits<double>::quiet_NaN();  ///< last commanded position
  };
  static constexpr int kNoAxis = -1;

  /// Reads axis i's present position (turns) on `bus`. Sets start_problem_ on failure.
  Status ask_position(FrameTransport& bus, std::size_t i, float* turns);
  Status start_axis(FrameTransport& bus, std::size_t i);
  /// Sends IDLE to axes [0, count), best effort.
  void idle_axes(FrameTransport& bus, std::size_t count);
  void take_heartbeat(std::size_t i, const odrive::Heartbeat& h) noexcept;
  std::string axis_problem(std::size_t i) const;

  OdriveDrivesConfig config_;
  std::vector<Axis> axes_;
  int axis_of_node_[odrive::kMaxNode + 1];
  std::string start_problem_;
  std::atomic<std::uint64_t> device_errors_{0};  ///< read from any thread (CanDrives contract)
};

}  // namespace avar::firmware_iface
