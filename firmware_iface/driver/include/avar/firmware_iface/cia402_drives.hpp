#pragma once
// CANopen drives with the CiA 402 profile in cyclic synchronous position mode
// (../shared/protocols/canopen-cia402.md), as one CanDrives set on a CAN link.
//
// start(), per drive: NMT reset communication and the boot-up; a Fault is reset (controlword
// 0x0080 then 0x0000); by SDO: modes of operation 0x6060 = 8 (CSP, confirmed in 0x6061), the
// heartbeat producer time 0x1017, RPDO1 = controlword + target position and TPDO1 = statusword +
// position actual value (each PDO invalidated, its mapping cleared, written, counted and the PDO
// made valid again, both synchronous: transmission type 1), the target set to the position
// actual value (so enabling does not jump); NMT start, an Operational heartbeat, then
// Shutdown -> Switch on -> Enable operation, each state confirmed in the statusword.
//
// Each tick: one RPDO1 per driven drive (controlword 0x000F, target counts), a drive released
// since the last tick gets controlword 0x0000 (disable voltage) once, then one SYNC; every drive
// answers the SYNC with TPDO1. take() reads TPDO1 (position telemetry; Fault, or Operation
// enabled left while driven -> kDeviceFaultState), heartbeats (an NMT state other than
// Operational while driven -> kDeviceFaultState) and EMCY (its error code kept for the message,
// its class mapped to DeviceFault bits while the drive is in Fault). settle(): a missing TPDO1
// makes the drive's feedback unknown and the tick a timeout; heartbeat_budget_ticks ticks in a row
// without a heartbeat -> kDeviceLost (DeviceWatch: device_watch.hpp).
//
// Units: each actuator's calibration maps channel units to position counts (the drive's user
// units). Threads and real-time rules: those of CanDrives.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/can_drives.hpp"
#include "avar/firmware_iface/canopen_codec.hpp"
#include "avar/firmware_iface/cia402_codec.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct Cia402Actuator {
  std::size_t channel = 0;        ///< rig channel index
  std::uint8_t node = 1;          ///< CANopen node ID, 1..127
  LinearCalibration calibration;  ///< channel units -> position counts (the drive's user units)
};

struct Cia402DrivesConfig {
  std::vector<Cia402Actuator> actuators;
  /// Heartbeat producer time written to every drive's 0x1017, ms (0: no heartbeat, no loss check).
  std::uint16_t heartbeat_ms = 100;
  /// Ticks in a row without a heartbeat that make a drive lost (kDeviceLost; its DeviceWatch
  /// budget); choose it above the heartbeat period in ticks (100 ms at 100 Hz: 10 ticks; 30
  /// leaves room). 0: no check.
  std::uint32_t heartbeat_budget_ticks = 30;
  /// Longest wait for each SDO answer during start() and read_positions().
  std::chrono::milliseconds sdo_timeout{50};
  /// Longest wait for the boot-up after NMT reset communication.
  std::chrono::milliseconds boot_timeout{1000};
  /// Longest wait for each CiA 402 state, for 0x6061 to show CSP, and for the Operational heartbeat.
  std::chrono::milliseconds state_timeout{500};
};

class Cia402Drives final : public CanDrives {
 public:
  /// Throws std::invalid_argument for a node out of 1..127 or used twice.
  explicit Cia402Drives(Cia402DrivesConfig config);

  const char* device_name() const noexcept override { return "CiA 402 drive"; }
  Status start(FrameTransport& bus) override;
  std::string start_problem() const override { return start_problem_; }
  /// SDO reads of 0x6064 (position actual value).
  Status read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) override;
  std::size_t max_tick_frames() const noexcept override { return drives_.size() + 1; }
  void encode_tick(std::span<const double> frame, CanOutbox& out) noexcept override;
  bool take(const CanFrame& frame) noexcept override;
  bool replies_complete() const noexcept override;
  Status settle() noexcept override;
  /// Controlword 0x0000 (disable voltage: the drives go to Switch on disabled, motors free) to
  /// every drive, then a SYNC (the RPDOs are synchronous).
  void encode_release(CanOutbox& out) noexcept override;
  /// "CiA 402 node 5: Fault (EMCY 0x7121)", "CiA 402 node 5: no heartbeat for 31 ticks".
  std::string channel_problem(std::size_t channel) const override;
  /// EMCY messages with a non-zero error code.
  std::uint64_t device_errors() const noexcept override { return device_errors_.load(std::memory_order_relaxed); }

  /// The CiA 402 state drive i (config order) last reported; its NMT state from its heartbeat.
  cia402::State drive_state(std::size_t i) const noexcept { return drives_[i].state; }
  canopen::NmtState nmt_state(std::size_t i) const noexcept { return drives_[i].nmt; }

 private:
  struct Drive {
    std::uint8_t node = 1;
    std::int32_t target = 0;               ///< last target sent, counts
    bool driven = false;                   ///< as of this tick's encode_tick
    bool tpdo_seen = false;                ///< this tick
    DeviceWatch tpdos{kStopWaitingAfter};  ///< lost: no longer waited for
    bool heartbeat_seen = false;           ///< this tick
    DeviceWatch heartbeat;                 ///< heartbeat silence, against the budget
    bool lost = false;                     ///< heartbeats watched and the budget ran out
    bool state_fault = false;              ///< Fault, or out of Operation enabled while driven (last TPDO1)
    bool nmt_fault = false;                ///< not Operational while driven (last heartbeat)
    std::uint16_t statusword = 0;
    cia402::State state = cia402::State::unknown;
    canopen::NmtState nmt = canopen::NmtState::pre_operational;
    std::uint16_t emcy_code = 0;  ///< last non-zero EMCY error code
  };

  /// A drive as before start(), its heartbeat watched against the budget.
  Drive new_drive(std::uint8_t node) const noexcept;
  /// Heartbeats are configured and a budget given.
  bool watch_heartbeats() const noexcept { return config_.heartbeat_ms > 0 && config_.heartbeat_budget_ticks > 0; }
  Status start_drive(FrameTransport& bus, Drive& d);
  /// One SDO write / read; on failure sets start_problem_ and returns the status.
  Status write(FrameTransport& bus, const Drive& d, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
               std::uint8_t size);
  Status read(FrameTransport& bus, const Drive& d, std::uint16_t index, std::uint8_t sub, std::uint32_t* value);
  /// Writes `controlword`, then reads the statusword until it shows `want`.
  Status command(FrameTransport& bus, Drive& d, std::uint16_t controlword, cia402::State want);
  Status read_state(FrameTransport& bus, Drive& d);
  /// Maps a PDO: invalidate, clear, entries, count, transmission type, valid again.
  Status map_pdo(FrameTransport& bus, const Drive& d, std::uint16_t communication, std::uint16_t mapping, std::uint32_t cob_id,
                 std::uint32_t first, std::uint32_t second);
  void fail(const Drive& d, const std::string& what);
  std::uint32_t faults_of(const Drive& d) const noexcept;
  Drive* find(std::uint8_t node) noexcept;

  Cia402DrivesConfig config_;
  std::vector<Drive> drives_;
  std::atomic<std::uint64_t> device_errors_{0};  ///< read from any thread (CanDrives contract)
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
