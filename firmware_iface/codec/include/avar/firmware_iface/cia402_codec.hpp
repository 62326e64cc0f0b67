#pragma once
// The CiA 402 drive profile (../shared/protocols/canopen-cia402.md, sections 5-7): object
// indices, controlword commands, the statusword's state decode (the masks of section 6), the
// power state machine's transitions as a drive applies them, and the two PDO layouts avar maps
// for cyclic synchronous position: RPDO controlword + target position, TPDO statusword +
// position actual value. Pure; no allocation, no exception: real-time safe.

#include <cstdint>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface::cia402 {

// ---- objects ---------------------------------------------------------------------------------

inline constexpr std::uint16_t kErrorCode = 0x603F;                ///< UINT16, RO: last fault's EMCY code
inline constexpr std::uint16_t kControlword = 0x6040;              ///< UINT16, RW, RPDO
inline constexpr std::uint16_t kStatusword = 0x6041;               ///< UINT16, RO, TPDO
inline constexpr std::uint16_t kModesOfOperation = 0x6060;         ///< INT8, RW
inline constexpr std::uint16_t kModesOfOperationDisplay = 0x6061;  ///< INT8, RO
inline constexpr std::uint16_t kPositionActual = 0x6064;           ///< INT32, RO, TPDO, user units (counts)
inline constexpr std::uint16_t kTargetPosition = 0x607A;           ///< INT32, RW, RPDO, user units (counts)
inline constexpr std::uint16_t kSoftwarePositionLimit = 0x607D;    ///< sub 1 min, sub 2 max: INT32, user units
inline constexpr std::uint16_t kProfileVelocity = 0x6081;          ///< UINT32
inline constexpr std::uint16_t kProfileAcceleration = 0x6083;      ///< UINT32
inline constexpr std::uint16_t kProfileDeceleration = 0x6084;      ///< UINT32
inline constexpr std::uint16_t kSupportedDriveModes = 0x6502;      ///< UINT32, RO

/// Modes of operation (0x6060 / 0x6061); negative values are vendor modes.
enum class Mode : std::int8_t {
  none = 0,
  profile_position = 1,
  velocity = 2,
  profile_velocity = 3,
  profile_torque = 4,
  homing = 6,
  interpolated_position = 7,
  cyclic_synchronous_position = 8,
  cyclic_synchronous_velocity = 9,
  cyclic_synchronous_torque = 10,
};
/// "cyclic synchronous position", "profile position"...; "vendor mode" / "unknown mode" otherwise.
const char* mode_name(std::int8_t mode) noexcept;
/// The bit of 0x6502 (supported drive modes) that says `mode` is supported; 0 for none.
std::uint32_t supported_mode_bit(std::int8_t mode) noexcept;

// ---- controlword -----------------------------------------------------------------------------

/// Controlword bits.
inline constexpr std::uint16_t kCwSwitchOn = 1u << 0;
inline constexpr std::uint16_t kCwEnableVoltage = 1u << 1;
inline constexpr std::uint16_t kCwQuickStop = 1u << 2;  ///< 0 = quick stop requested
inline constexpr std::uint16_t kCwEnableOperation = 1u << 3;
inline constexpr std::uint16_t kCwFaultReset = 1u << 7;  ///< acts on its rising edge
inline constexpr std::uint16_t kCwHalt = 1u << 8;

/// Controlword commands (values written to 0x6040).
inline constexpr std::uint16_t kShutdown = 0x0006;
inline constexpr std::uint16_t kSwitchOn = 0x0007;
inline constexpr std::uint16_t kDisableOperation = 0x0007;
inline constexpr std::uint16_t kEnableOperation = 0x000F;
inline constexpr std::uint16_t kDisableVoltage = 0x0000;
inline constexpr std::uint16_t kQuickStop = 0x0002;
inline constexpr std::uint16_t kFaultReset = 0x0080;

/// Which command a controlword gives (bit patterns of CiA 402; bit 7 set matches none of the
/// others, so a fault reset never also switches anything on).
constexpr bool is_shutdown(std::uint16_t cw) noexcept { return (cw & 0x87) == 0x06; }
/// Switch on, with or without enable operation (bit 3 free: 0x000F from Ready to switch on takes
/// transitions 3 and 4).
constexpr bool is_switch_on(std::uint16_t cw) noexcept { return (cw & 0x87) == 0x07; }
constexpr bool is_disable_voltage(std::uint16_t cw) noexcept { return (cw & 0x82) == 0x00; }
constexpr bool is_quick_stop(std::uint16_t cw) noexcept { return (cw & 0x86) == 0x02; }
constexpr bool is_disable_operation(std::uint16_t cw) noexcept { return (cw & 0x8F) == 0x07; }
constexpr bool is_enable_operation(std::uint16_t cw) noexcept { return (cw & 0x8F) == 0x0F; }

// ---- statusword and states ---------------------------------------------------------------------

/// Statusword bits beyond the state bits (0-3, 5, 6).
inline constexpr std::uint16_t kSwVoltageEnabled = 1u << 4;
inline constexpr std::uint16_t kSwQuickStop = 1u << 5;  ///< 0 = quick stop active
inline constexpr std::uint16_t kSwWarning = 1u << 7;
inline constexpr std::uint16_t kSwRemote = 1u << 9;
inline constexpr std::uint16_t kSwTargetReached = 1u << 10;
inline constexpr std::uint16_t kSwInternalLimit = 1u << 11;
/// PP: set-point acknowledge; CSP: the drive follows the target.
inline constexpr std::uint16_t kSwSetPointAcknowledge = 1u << 12;
inline constexpr std::uint16_t kSwFollowingError = 1u << 13;

enum class State : std::uint8_t {
  not_ready_to_switch_on,
  switch_on_disabled,
  ready_to_switch_on,
  switched_on,
  operation_enabled,
  quick_stop_active,
  fault_reaction_active,
  fault,
  unknown,  ///< a statusword no row of the table matches
};

/// The state a statusword reports (`statusword & mask == value`, table of section 6).
State decode_state(std::uint16_t statusword) noexcept;
/// The state bits a drive in `state` reports (the table's value; 0 for unknown).
std::uint16_t state_bits(State state) noexcept;
/// "Operation enabled", "Fault"...
const char* state_name(State state) noexcept;
/// Fault or fault reaction active.
constexpr bool is_fault(State s) noexcept { return s == State::fault || s == State::fault_reaction_active; }

/// One step of the power state machine as a drive applies a controlword: the state after
/// `controlword` arrives in `state` (the previous controlword tells the fault-reset edge), and
/// the transition number of the table (2..12, 15, 16), or 0 when nothing changes. Automatic
/// transitions (0, 1, 13, 14) are the drive's own. From Ready to switch on, a switch on with
/// bit 3 set takes transition 3 only; apply it again for 4.
struct Transition {
  State to = State::unknown;
  int number = 0;
};
Transition next_state(State state, std::uint16_t controlword, std::uint16_t previous_controlword) noexcept;

// ---- EMCY error codes --------------------------------------------------------------------------

/// DeviceFault bits an EMCY error code stands for (its class: 0x2xxx current -> electrical,
/// 0x3xxx voltage, 0x4xxx temperature -> overheat, 0x73xx sensor -> encoder, 0x8311 / 0x7121
/// overload; anything else non-zero -> other); 0 for 0x0000 (no error).
std::uint32_t emcy_device_faults(std::uint16_t error_code) noexcept;

// ---- the PDOs avar maps ------------------------------------------------------------------------

/// RPDO payload: controlword (UINT16) + target position (INT32), 6 bytes.
CanFrame encode_control_target(std::uint32_t cob_id, std::uint16_t controlword, std::int32_t target) noexcept;
/// False unless `frame` carries at least 6 data bytes on `cob_id`.
bool decode_control_target(const CanFrame& frame, std::uint32_t cob_id, std::uint16_t* controlword,
                           std::int32_t* target) noexcept;
/// TPDO payload: statusword (UINT16) + position actual value (INT32), 6 bytes.
CanFrame encode_status_position(std::uint32_t cob_id, std::uint16_t statusword, std::int32_t position) noexcept;
bool decode_status_position(const CanFrame& frame, std::uint32_t cob_id, std::uint16_t* statusword,
                            std::int32_t* position) noexcept;

}  // namespace avar::firmware_iface::cia402
