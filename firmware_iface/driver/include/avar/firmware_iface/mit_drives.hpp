#pragma once
// MIT mini-cheetah style CAN motors (../shared/protocols/mit-cheetah-can.md) as one CanDrives set:
// each tick one impedance command per driven motor (position from the calibration, velocity 0,
// the configured kp and kd, no feed-forward torque), and the reply every motor sends to every
// frame it accepts (to the master ID, byte 0 = its ID) refreshes its position (channel units) and
// load (measured torque over the torque limit, t_max for symmetric ranges; MIT replies carry no
// temperature and no error).
//
// Velocity: the command's velocity target is 0, not a finite difference of consecutive ticks.
// The drive set has no clock (silence is judged in ticks), a jump in the stream would become a
// velocity spike, and a stale velocity target would keep pushing after the stream stopped. The
// price is a lag behind a ramp of speed w of kd·w/kp (the damping pulls toward rest).
//
// Threads and real-time safety: as CanDrives.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/can_drives.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/firmware_iface/mit_can_codec.hpp"

namespace avar::firmware_iface {

struct MitActuator {
  std::size_t channel = 0;                          ///< rig channel index
  std::uint32_t node = 1;                           ///< CAN_ID, 1..0x7FF, not the master ID
  mit::MitRanges ranges = mit::kMiniCheetahRanges;  ///< the motor model's value ranges
  double kp = 20;                                   ///< stiffness, N·m/rad, 0..ranges.kp_max
  double kd = 0.5;                                  ///< damping, N·m·s/rad, 0..ranges.kd_max
  /// Channel units -> motor radians (after the motor's zero); its window must lie inside
  /// [ranges.p_min, ranges.p_max].
  LinearCalibration calibration{0, 1, -1, 1};
};

struct MitDrivesConfig {
  std::vector<MitActuator> actuators;
  /// Ticks in a row without a reply from a commanded motor that make it lost (kDeviceLost; its
  /// DeviceWatch budget, device_watch.hpp).
  std::uint32_t reply_budget_ticks = 10;
  /// Longest wait for each answer during start() and read_positions().
  std::chrono::milliseconds start_timeout{50};
  /// CAN_MASTER: the standard ID the motors reply to (firmware default 0).
  std::uint32_t master_id = 0;
  /// How the motors' replies are laid out (clones: longer replies, error bits in byte 0).
  mit::MitReplyFormat reply_format;
};

class MitDrives final : public CanDrives {
 public:
  /// Checks the config: valid ranges, nodes in 1..0x7FF, distinct, none the master ID, and
  /// telling apart in replies (byte 0 under the ID mask); kp and kd within the ranges; each
  /// calibration's window inside the position range; a reply budget of at least one tick.
  /// Throws std::invalid_argument naming the motor. Sizes everything.
  explicit MitDrives(MitDrivesConfig config);

  const char* device_name() const noexcept override { return "MIT motor"; }

  /// Per motor: enters motor mode and takes its reply (the present position), then commands that
  /// position with the configured gains (no jump) and takes that reply. A motor that does not
  /// answer, or stands outside its calibrated window (by more than a position quantum), fails
  /// the start (start_problem() names it); every motor already entered is told to exit motor
  /// mode then.
  Status start(FrameTransport& bus) override;
  std::string start_problem() const override { return start_problem_; }

  /// Asks each motor with a frame that changes nothing (its last command once started, exit
  /// motor mode before) and reads the position from its reply.
  Status read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) override;

  std::size_t max_tick_frames() const noexcept override { return motors_.size(); }
  void encode_tick(std::span<const double> frame, CanOutbox& out) noexcept override;
  bool take(const CanFrame& frame) noexcept override;
  bool replies_complete() const noexcept override;
  Status settle() noexcept override;
  void encode_release(CanOutbox& out) noexcept override;
  /// "MIT motor 3: no reply for 12 ticks"; empty while every motor of the channel answers.
  std::string channel_problem(std::size_t channel) const override;
  /// MIT replies carry no error field: always 0.
  std::uint64_t device_errors() const noexcept override { return 0; }

  /// The device position (rad) last commanded to actuator i.
  double last_command(std::size_t i) const noexcept { return motors_[i].command; }

 private:
  struct Motor {
    std::uint8_t reply_id = 0;  // byte 0 of its replies, under the ID mask
    double command = 0;         // rad, last position commanded
    bool started = false;       // in motor mode by our start()
    bool expected = false;      // sent a frame this tick
    bool replied = false;       // answered this tick
    DeviceWatch replies;        // reply silence, against the budget
  };

  /// A motor as before start(), its replies watched against the budget.
  Motor new_motor(std::uint8_t reply_id) const noexcept;
  CanFrame hold_frame(std::size_t i) const noexcept;
  bool is_reply_of(const CanFrame& frame, std::size_t i, mit::MitReply* reply) const noexcept;
  void record_reply(std::size_t i, const mit::MitReply& reply) noexcept;
  std::string motor_name(std::size_t i) const;
  void exit_started(FrameTransport& bus);

  MitDrivesConfig config_;
  std::vector<Motor> motors_;
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
