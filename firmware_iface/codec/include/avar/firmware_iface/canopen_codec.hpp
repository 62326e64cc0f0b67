#pragma once
// CANopen CiA 301 (../shared/protocols/canopen-cia402.md, sections 1-4): pure encoders and
// decoders of the frames a CANopen master and its drives exchange: COB-IDs of the pre-defined
// connection set, NMT commands, heartbeat and boot-up, SYNC, EMCY, expedited SDO transfers and
// their aborts, PDO mapping entries. No I/O, no clock, no allocation, no exception: every
// function is real-time safe. Classic CAN, 11-bit identifiers; all object data little-endian.

#include <array>
#include <cstdint>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface::canopen {

inline constexpr std::uint8_t kMaxNode = 127;
constexpr bool valid_node(std::uint8_t node) noexcept { return node >= 1 && node <= kMaxNode; }

// ---- COB-IDs (pre-defined connection set) ---------------------------------------------------

inline constexpr std::uint32_t kNmtCobId = 0x000;
inline constexpr std::uint32_t kSyncCobId = 0x080;
inline constexpr std::uint32_t kTimeCobId = 0x100;

constexpr std::uint32_t emcy_cob_id(std::uint8_t node) noexcept { return 0x080u + node; }
/// TPDO `pdo` (1..4) of `node`: 0x180 / 0x280 / 0x380 / 0x480 + node (drive -> master).
constexpr std::uint32_t tpdo_cob_id(int pdo, std::uint8_t node) noexcept {
  return 0x180u + 0x100u * static_cast<std::uint32_t>(pdo - 1) + node;
}
/// RPDO `pdo` (1..4) of `node`: 0x200 / 0x300 / 0x400 / 0x500 + node (master -> drive).
constexpr std::uint32_t rpdo_cob_id(int pdo, std::uint8_t node) noexcept {
  return 0x200u + 0x100u * static_cast<std::uint32_t>(pdo - 1) + node;
}
/// SDO server -> client (responses): 0x580 + node.
constexpr std::uint32_t sdo_response_cob_id(std::uint8_t node) noexcept { return 0x580u + node; }
/// SDO client -> server (requests): 0x600 + node.
constexpr std::uint32_t sdo_request_cob_id(std::uint8_t node) noexcept { return 0x600u + node; }
/// NMT error control (heartbeat, boot-up): 0x700 + node.
constexpr std::uint32_t heartbeat_cob_id(std::uint8_t node) noexcept { return 0x700u + node; }

enum class CobFunction : std::uint8_t {
  nmt,
  sync,
  emcy,
  time,
  tpdo1,
  rpdo1,
  tpdo2,
  rpdo2,
  tpdo3,
  rpdo3,
  tpdo4,
  rpdo4,
  sdo_response,
  sdo_request,
  heartbeat,
  unknown,
};

struct CobId {
  CobFunction function = CobFunction::unknown;
  std::uint8_t node = 0;  ///< 0 for the broadcast objects (NMT, SYNC, TIME)
};

/// Which object of the pre-defined connection set an 11-bit identifier is. Identifiers with a
/// node part out of 1..127 (except NMT, SYNC, TIME) are unknown.
CobId decode_cob_id(std::uint32_t id) noexcept;

// ---- NMT, heartbeat, SYNC --------------------------------------------------------------------

enum class NmtCommand : std::uint8_t {
  start = 0x01,                  ///< -> Operational
  stop = 0x02,                   ///< -> Stopped
  enter_pre_operational = 0x80,  ///< -> Pre-operational
  reset_node = 0x81,
  reset_communication = 0x82,
};

/// The state byte of a heartbeat (bit 7, the node-guarding toggle, masked off).
enum class NmtState : std::uint8_t {
  boot_up = 0x00,  ///< sent once after a reset; the node is then Pre-operational
  stopped = 0x04,
  operational = 0x05,
  pre_operational = 0x7F,
};

/// NMT command to `node` (0 = every node): 2 bytes on COB-ID 0x000.
CanFrame encode_nmt(NmtCommand command, std::uint8_t node) noexcept;
/// False unless `frame` is a 2-byte NMT command.
bool decode_nmt(const CanFrame& frame, NmtCommand* command, std::uint8_t* node) noexcept;

/// Heartbeat (or boot-up, NmtState::boot_up) of `node`: 1 byte on 0x700 + node.
CanFrame encode_heartbeat(std::uint8_t node, NmtState state) noexcept;
/// False unless `frame` is a heartbeat of a node 1..127; *state is the byte & 0x7F (any value).
bool decode_heartbeat(const CanFrame& frame, std::uint8_t* node, NmtState* state) noexcept;
/// "boot-up", "Stopped", "Operational", "Pre-operational"; "unknown NMT state" otherwise.
const char* nmt_state_name(NmtState state) noexcept;

/// SYNC: COB-ID 0x080, no data.
CanFrame encode_sync() noexcept;
/// A SYNC, with or without the optional 1-byte counter.
bool is_sync(const CanFrame& frame) noexcept;

// ---- EMCY ------------------------------------------------------------------------------------

struct Emcy {
  std::uint16_t error_code = 0;     ///< 0x0000 = error reset / no error
  std::uint8_t error_register = 0;  ///< object 0x1001 (bit 0 generic error)
  std::array<std::uint8_t, 5> vendor{};
};

/// EMCY of `node`: 8 bytes on 0x080 + node.
CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept;
/// False unless `frame` is an 8-byte EMCY of a node 1..127.
bool decode_emcy(const CanFrame& frame, std::uint8_t* node, Emcy* emcy) noexcept;

// ---- SDO (expedited) -------------------------------------------------------------------------

/// SDO abort codes (bytes 4-7 of an abort frame).
enum SdoAbortCode : std::uint32_t {
  kSdoAbortTimeout = 0x05040000,
  kSdoAbortInvalidCommand = 0x05040001,
  kSdoAbortUnsupportedAccess = 0x06010000,
  kSdoAbortReadWriteOnly = 0x06010001,
  kSdoAbortWriteReadOnly = 0x06010002,
  kSdoAbortNoObject = 0x06020000,
  kSdoAbortCannotMap = 0x06040041,
  kSdoAbortPdoTooLong = 0x06040042,
  kSdoAbortLengthMismatch = 0x06070010,
  kSdoAbortLengthTooHigh = 0x06070012,
  kSdoAbortLengthTooLow = 0x06070013,
  kSdoAbortNoSubIndex = 0x06090011,
  kSdoAbortValueRange = 0x06090030,
  kSdoAbortValueTooHigh = 0x06090031,
  kSdoAbortValueTooLow = 0x06090032,
  kSdoAbortGeneral = 0x08000000,
  kSdoAbortLocalControl = 0x08000021,
  kSdoAbortDeviceState = 0x08000022,
};

/// "SDO timeout", "write to read-only object"...; "unknown abort code" for others.
const char* sdo_abort_name(std::uint32_t code) noexcept;

enum class SdoKind : std::uint8_t {
  download_request,   ///< client writes (0x2x)
  download_response,  ///< server confirms a write (0x60)
  upload_request,     ///< client reads (0x40)
  upload_response,    ///< server answers a read (0x4x)
  abort,              ///< either side (0x80)
  other,              ///< segmented or block transfer frames: not expedited, not decoded further
};

/// One SDO frame, decoded.
struct Sdo {
  SdoKind kind = SdoKind::other;
  std::uint8_t command = 0;  ///< byte 0 as received
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  /// Download request / upload response: the value (unused bytes as sent); abort: the code.
  std::uint32_t data = 0;
  /// Download request / upload response: bytes of data 1..4, 0 = size not indicated.
  std::uint8_t size = 0;
  /// Download request / upload response: an expedited transfer (false: a segmented one starts).
  bool expedited = true;
};

/// Write request: `size` (1..4) bytes of `value` to index:sub of `node` (0x2F/0x2B/0x27/0x23).
CanFrame encode_sdo_download(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                             std::uint8_t size) noexcept;
/// The server's confirmation of a write (0x60, index and sub echoed).
CanFrame encode_sdo_download_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept;
/// Read request (0x40).
CanFrame encode_sdo_upload(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept;
/// The server's answer to a read: `size` (1..4) bytes of `value` (0x4F/0x4B/0x47/0x43).
CanFrame encode_sdo_upload_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                                    std::uint8_t size) noexcept;
/// An abort; `from_server` picks 0x580 + node (true) or 0x600 + node (false).
CanFrame encode_sdo_abort(std::uint8_t node, bool from_server, std::uint16_t index, std::uint8_t sub,
                          std::uint32_t code) noexcept;

/// False unless `frame` is an 8-byte frame on 0x580 + node or 0x600 + node (node 1..127).
/// *from_server tells which of the two.
bool decode_sdo(const CanFrame& frame, std::uint8_t* node, bool* from_server, Sdo* sdo) noexcept;

/// `value` cut to `size` bytes (1..4), sign-extended when `is_signed`, as an int64.
std::int64_t sdo_value(std::uint32_t value, std::uint8_t size, bool is_signed) noexcept;

// ---- PDOs ------------------------------------------------------------------------------------

/// Communication parameter objects: 0x1400 + k (RPDO k+1), 0x1800 + k (TPDO k+1);
/// mapping: 0x1600 + k, 0x1A00 + k.
inline constexpr std::uint16_t kRpdoCommunication = 0x1400;
inline constexpr std::uint16_t kRpdoMapping = 0x1600;
inline constexpr std::uint16_t kTpdoCommunication = 0x1800;
inline constexpr std::uint16_t kTpdoMapping = 0x1A00;
inline constexpr std::uint16_t kDeviceType = 0x1000;
inline constexpr std::uint16_t kErrorRegister = 0x1001;
inline constexpr std::uint16_t kHeartbeatProducerTime = 0x1017;  ///< UINT16, ms, 0 = off

/// Bit 31 of a PDO COB-ID entry (sub 1): the PDO does not exist (invalid).
inline constexpr std::uint32_t kPdoInvalid = 0x80000000u;
/// Bit 30: no RTR allowed on this PDO.
inline constexpr std::uint32_t kPdoNoRtr = 0x40000000u;

/// Transmission types (sub 2): 0 synchronous acyclic, 1..240 every n-th SYNC, 0xFC/0xFD on RTR
/// only, 0xFE manufacturer event, 0xFF profile event.
inline constexpr std::uint8_t kPdoSyncAcyclic = 0x00;
inline constexpr std::uint8_t kPdoSyncMaxCycle = 240;
inline constexpr std::uint8_t kPdoRtrSync = 0xFC;
inline constexpr std::uint8_t kPdoRtrEvent = 0xFD;
inline constexpr std::uint8_t kPdoEventManufacturer = 0xFE;
inline constexpr std::uint8_t kPdoEventProfile = 0xFF;

struct PdoMapping {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;
  bool operator==(const PdoMapping&) const = default;
};

/// A mapping entry as written to 0x1600+k / 0x1A00+k: index << 16 | sub << 8 | bits.
constexpr std::uint32_t pdo_mapping_entry(std::uint16_t index, std::uint8_t sub, std::uint8_t bits) noexcept {
  return static_cast<std::uint32_t>(index) << 16 | static_cast<std::uint32_t>(sub) << 8 | bits;
}
constexpr std::uint32_t pdo_mapping_entry(const PdoMapping& m) noexcept { return pdo_mapping_entry(m.index, m.sub, m.bits); }
constexpr PdoMapping decode_pdo_mapping(std::uint32_t entry) noexcept {
  return {static_cast<std::uint16_t>(entry >> 16), static_cast<std::uint8_t>(entry >> 8), static_cast<std::uint8_t>(entry)};
}

}  // namespace avar::firmware_iface::canopen
