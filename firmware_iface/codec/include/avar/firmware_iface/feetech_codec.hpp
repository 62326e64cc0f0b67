#pragma once
// Feetech SCS / STS / SMS serial bus servos (../shared/protocols/feetech-sts.md): pure encoders
// and decoders. No I/O, no clock, no allocation, no exception: every function except the
// describe_*() ones is real-time safe.
//
// Packets (both directions): FF FF ID LEN CODE PARAMS... CHECKSUM, LEN = params + 2, CODE the
// instruction (host -> servo) or the error byte (servo -> host), CHECKSUM = ~(ID + LEN + CODE +
// sum of params). No byte stuffing. Encoders write one packet into `out` and return its length,
// or 0 (writing nothing useful) when `out` is too small or an argument is invalid.
//
// Two-byte registers are little-endian on STS/SMS and big-endian on SCS; signed registers are
// sign-magnitude (a sign bit, the rest magnitude) with the sign bit per register (bit 15 for
// positions and speeds, bit 10 for load).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace avar::firmware_iface::feetech {

enum class Series : std::uint8_t {
  sts,  ///< STS/SMS: little-endian words, 4096 steps per turn
  scs,  ///< SCS: big-endian words, 1024 counts over the range
};

inline constexpr std::uint8_t kBroadcastId = 0xFE;
/// Highest unicast ID (0xFE is broadcast; 0xFF would read as a header byte).
inline constexpr std::uint8_t kMaxId = 253;
inline constexpr std::size_t kHeaderSize = 4;  ///< FF FF ID LEN
inline constexpr std::size_t kMinPacketSize = 6;
/// Largest packet: LEN is one byte, so 4 + 255.
inline constexpr std::size_t kMaxPacketSize = kHeaderSize + 255;

enum Instruction : std::uint8_t {
  kPing = 0x01,
  kRead = 0x02,
  kWrite = 0x03,
  kRegWrite = 0x04,
  kAction = 0x05,
  kRecovery = 0x06,
  kReset = 0x0A,
  kSyncRead = 0x82,
  kSyncWrite = 0x83,
};

/// Control-table addresses avar uses (same on SCS and STS unless named).
enum Address : std::uint8_t {
  kModelNumber = 3,
  kId = 5,
  kBaudRate = 6,
  kReturnDelay = 7,    ///< 2 µs per unit
  kResponseLevel = 8,  ///< 0: only Read and Ping answer; 1: every non-broadcast instruction
  kMinPositionLimit = 9,
  kMaxPositionLimit = 11,
  kMaxTemperature = 13,
  kUnloadingCondition = 19,
  kTorqueEnable = 40,
  kAcceleration = 41,  ///< 100 steps/s² per unit, 0 = maximum
  kGoalPosition = 42,
  kGoalTime = 44,
  kGoalSpeed = 46,  ///< steps/s (STS3215 factory unit), 0 = maximum
  kLockScs = 48,
  kLockSts = 55,
  kPresentPosition = 56,
  kPresentSpeed = 58,
  kPresentLoad = 60,         ///< 0.1 % of full duty, sign bit 10
  kPresentVoltage = 62,      ///< 0.1 V
  kPresentTemperature = 63,  ///< °C
  kStatus = 65,              ///< same bits as the status packet's error byte
  kMoving = 66,
};

/// Bits of the status packet's error byte (and the Status register). Voltage to overload are the
/// FT SDK's; checksum, range and instruction follow DYNAMIXEL Protocol 1.0, which the FT-SCS
/// protocol derives from (a third-party Feetech SDK port uses the same values; unconfirmed on
/// hardware). Range shares bit 3 with over-current: it only appears in the reply to the
/// offending instruction, never in the Status register.
enum ErrorBit : std::uint8_t {
  kErrorVoltage = 0x01,
  kErrorAngleSensor = 0x02,
  kErrorOverheat = 0x04,
  kErrorOverCurrent = 0x08,
  kErrorRange = 0x08,
  kErrorChecksum = 0x10,
  kErrorOverload = 0x20,
  kErrorInstruction = 0x40,
};

/// Sign bit of each signed register.
inline constexpr int kPositionSignBit = 15;
inline constexpr int kSpeedSignBit = 15;
inline constexpr int kLoadSignBit = 10;

/// Position steps over the full range: 4096 per turn on STS, 1024 counts on SCS.
constexpr int position_resolution(Series s) noexcept { return s == Series::sts ? 4096 : 1024; }

/// Sign-magnitude with the sign in bit `sign_bit` (1..15); the magnitude saturates at
/// 2^sign_bit - 1, never wraps.
std::uint16_t to_sign_magnitude(int value, int sign_bit) noexcept;
int from_sign_magnitude(std::uint16_t raw, int sign_bit) noexcept;

/// Position register value (goal, present) for a position in steps: sign-magnitude with the
/// sign in bit 15 on STS, unsigned on SCS; saturates, never wraps.
std::uint16_t position_word(Series series, long steps) noexcept;
int position_from_word(Series series, std::uint16_t raw) noexcept;

/// Two-byte register value in the series' byte order.
void put_word(Series series, std::span<std::uint8_t, 2> out, std::uint16_t value) noexcept;
std::uint16_t get_word(Series series, std::span<const std::uint8_t> in) noexcept;  ///< in.size() >= 2

/// ~(sum of bytes) & 0xFF: pass everything from ID to the last parameter.
std::uint8_t checksum(std::span<const std::uint8_t> bytes) noexcept;

/// Any packet: instruction (code = instruction) or status (code = error byte).
std::size_t encode_packet(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t code,
                          std::span<const std::uint8_t> params) noexcept;

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) noexcept;
std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address, std::uint8_t length) noexcept;
std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                         std::span<const std::uint8_t> data) noexcept;
/// Write of one two-byte register in the series' byte order.
std::size_t encode_write_word(std::span<std::uint8_t> out, Series series, std::uint8_t id, std::uint8_t address,
                              std::uint16_t value) noexcept;
/// Sync Write of `length` bytes at `address`: data holds ids.size() * length bytes, one block per
/// id in order (broadcast packet; no servo replies).
std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data) noexcept;
/// Sync Write of one two-byte register per id (values[i] for ids[i]), e.g. goal positions.
std::size_t encode_sync_write_words(std::span<std::uint8_t> out, Series series, std::uint8_t address,
                                    std::span<const std::uint8_t> ids, std::span<const std::uint16_t> values) noexcept;
/// Sync Read of `length` bytes at `address` from each of `ids`; each answers with its own status
/// packet, in the order listed.
std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t length,
                             std::span<const std::uint8_t> ids) noexcept;

/// Sizes on the wire, for link budgets.
constexpr std::size_t sync_write_size(std::size_t length, std::size_t servos) noexcept { return 8 + (length + 1) * servos; }
constexpr std::size_t sync_read_size(std::size_t servos) noexcept { return 8 + servos; }
constexpr std::size_t status_size(std::size_t data_length) noexcept { return 6 + data_length; }

struct Packet {
  std::uint8_t id = 0;
  std::uint8_t code = 0;                 ///< instruction, or the error byte of a status packet
  std::span<const std::uint8_t> params;  ///< points into the input
};

// clang-format 14 misreads an attribute on an enum and indents it:
// clang-format off
enum class [[nodiscard]] DecodeResult {
  ok,
  need_more,     ///< a packet may have started but is not complete
  bad_checksum,  ///< a whole packet arrived with a wrong checksum (*consumed covers it)
  bad_framing,   ///< bytes that cannot start a packet (*consumed says how many to drop)
};
// clang-format on

/// Looks for one packet at the start of `in`. bad_framing: skip *consumed bytes and try again
/// (garbage before a header, a third FF, a length below 2). need_more: *consumed is 0 (or the
/// garbage before a trailing FF) and nothing is lost by waiting. ok / bad_checksum: *consumed
/// covers the whole packet.
DecodeResult decode_packet(std::span<const std::uint8_t> in, Packet* packet, std::size_t* consumed) noexcept;

/// Names of the error bits of a status reply, for messages (allocates).
std::string describe_error(std::uint8_t error);

}  // namespace avar::firmware_iface::feetech
