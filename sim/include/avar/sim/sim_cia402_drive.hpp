#pragma once
// A simulated CANopen servo drive with the CiA 402 profile (../shared/protocols/canopen-cia402.md)
// on a simulated CAN bus: an object dictionary of the objects avar uses (types, access, ranges:
// SDO writes and reads answered with the aborts of CiA 301), the NMT state machine (boot-up after
// every reset, heartbeat producer per 0x1017), an expedited SDO server, four RPDOs and four
// TPDOs configurable through SDO (communication 0x1400/0x1800, mapping 0x1600/0x1A00; changes
// only while the PDO is invalid), SYNC-driven TPDOs and synchronous RPDOs (applied at the next
// SYNC), PDOs only in Operational, the whole power state machine of CiA 402 (quick stop stays
// in Quick stop active, as with quick stop option codes 5-8), and cyclic synchronous position:
// in Operation enabled the drive's position loop follows 0x607A on a CanMotorModel. Only CSP
// moves the motor; another supported mode holds the position where Operation enabled began.
//
// Units: positions in counts (the drive's user units), `counts_per_turn` counts per motor
// revolution (the model's radians times counts_per_turn / 2π). Time in seconds.
// Not thread-safe: its bus serialises every call.

#include <array>
#include <cstdint>
#include <deque>

#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/canopen_codec.hpp"
#include "avar/firmware_iface/cia402_codec.hpp"
#include "avar/sim/can_motor_model.hpp"
#include "avar/sim/can_node.hpp"
#include "avar/sim/canopen_object_dictionary.hpp"

namespace avar::sim {

struct SimCia402DriveConfig {
  std::uint8_t node = 1;                    ///< 1..127
  double counts_per_turn = 65536;           ///< position counts per motor revolution (> 0)
  std::int32_t initial_position = 0;        ///< counts, where the rotor rests at power-up
  std::int32_t position_min = -(1 << 30);   ///< 0x607D:01 software limit, counts
  std::int32_t position_max = 1 << 30;      ///< 0x607D:02
  std::uint32_t supported_modes = 1u << 7;  ///< 0x6502 bits (default: CSP only)
  std::uint16_t heartbeat_ms = 0;           ///< 0x1017 after a reset (0: no heartbeat)
  double kp = 30;                           ///< position-loop stiffness, N·m/rad (critically damped)
  double fault_reaction_s = 0.005;          ///< time in Fault reaction active before Fault
  double init_s = 0.002;                    ///< time in Not ready to switch on after a reset
  CanMotorParams motor;                     ///< its encoder resolution is set to counts_per_turn
};

class SimCia402Drive final : public CanNode {
 public:
  /// Powers up: reset node (boot-up queued, Pre-operational, Not ready to switch on). Throws
  /// std::invalid_argument for a node out of 1..127 or counts_per_turn <= 0.
  explicit SimCia402Drive(SimCia402DriveConfig config);

  void receive(const firmware_iface::CanFrame& frame) override;
  bool peek_transmit(firmware_iface::CanFrame* frame) const override;
  void pop_transmit() override;
  void advance(double dt_s) override;

  // ---- ground truth and state, for tests and the simulated figure -----------------------------
  double position_counts() const noexcept;  ///< the rotor's true position, counts
  firmware_iface::cia402::State state() const noexcept { return state_; }
  std::uint16_t statusword() const noexcept;
  std::uint16_t controlword() const noexcept { return static_cast<std::uint16_t>(od_.get(0x6040, 0)); }
  firmware_iface::canopen::NmtState nmt_state() const noexcept { return nmt_; }
  /// The number of the last power-state transition (0..16, CiA 402's table).
  int last_transition() const noexcept { return last_transition_; }
  /// An object's value as the drive holds it (0 when it does not exist).
  std::int64_t object(std::uint16_t index, std::uint8_t sub = 0) const noexcept { return od_.value(index, sub); }
  std::uint64_t sdo_aborts_sent() const noexcept { return sdo_aborts_; }
  std::uint64_t syncs() const noexcept { return syncs_; }

  // ---- fault injection --------------------------------------------------------------------------
  /// A fault inside the drive: EMCY with `emcy_code` (0x603F and 0x1001 set), Fault reaction
  /// active (the motor holds), then Fault (the motor is free) after fault_reaction_s.
  void raise_fault(std::uint16_t emcy_code);
  /// Stops (true) or resumes the heartbeat producer while everything else goes on.
  void set_heartbeat_silent(bool silent) noexcept { heartbeat_silent_ = silent; }
  /// A load torque on the rotor, N·m.
  void set_external_torque(double torque) noexcept { motor_.set_external_torque(torque); }

 private:
  static constexpr int kPdos = 4;
  struct Pdo {
    std::array<std::uint8_t, 8> pending{};  ///< RPDO: data received, waiting for SYNC
    bool has_pending = false;
    std::uint32_t syncs = 0;             ///< TPDO: SYNCs since it was last sent
    std::array<std::uint8_t, 8> last{};  ///< TPDO: data last sent (change detection)
    bool sent = false;
  };

  void build_dictionary();
  void reset_communication();
  void reset_application();
  void on_nmt(firmware_iface::canopen::NmtCommand command);
  void on_sdo(const firmware_iface::canopen::Sdo& sdo);
  void sdo_abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code);
  /// The device's own checks of a write the dictionary accepted: 0 or an abort code.
  std::uint32_t validate(const ObjectEntry& entry, std::uint32_t raw) const;
  /// Stores a value (from SDO or an RPDO) and does what writing it means.
  void apply(ObjectEntry& entry, std::uint32_t raw);
  void on_controlword(std::uint16_t cw, std::uint16_t previous);
  void on_target(std::int32_t target, std::int32_t previous);
  void enter(firmware_iface::cia402::State to, int transition);
  void on_sync();
  void on_rpdo(int k, const firmware_iface::CanFrame& frame);
  void apply_rpdo(int k);
  /// Bytes a PDO's mapping fills.
  int pdo_bytes(std::uint16_t mapping_index) const;
  firmware_iface::CanFrame tpdo_frame(int k) const;
  void send_tpdo(int k);
  void send_event_tpdos();
  bool pdo_valid(std::uint16_t communication_index) const;
  void refresh();
  void send(const firmware_iface::CanFrame& frame) { tx_.push_back(frame); }
  void send_emcy(std::uint16_t code, std::uint8_t error_register);

  SimCia402DriveConfig config_;
  CanopenObjectDictionary od_;
  CanMotorModel motor_;
  std::deque<firmware_iface::CanFrame> tx_;
  std::array<Pdo, kPdos> rpdos_{};
  std::array<Pdo, kPdos> tpdos_{};

  firmware_iface::canopen::NmtState nmt_ = firmware_iface::canopen::NmtState::pre_operational;
  firmware_iface::cia402::State state_ = firmware_iface::cia402::State::not_ready_to_switch_on;
  int last_transition_ = 0;
  double time_s_ = 0;
  double state_timer_s_ = 0;      ///< Not ready / Fault reaction active: time left
  double heartbeat_timer_s_ = 0;  ///< since the last heartbeat
  bool heartbeat_silent_ = false;
  double hold_rad_ = 0;             ///< where the motor holds in Quick stop / Fault reaction
  double target_time_s_ = -1;       ///< when 0x607A last changed
  double feedforward_rad_s_ = 0;    ///< target velocity of the last target step
  double feedforward_until_s_ = 0;  ///< the feedforward lapses when no new target comes
  std::uint64_t sdo_aborts_ = 0;
  std::uint64_t syncs_ = 0;
};

}  // namespace avar::sim
