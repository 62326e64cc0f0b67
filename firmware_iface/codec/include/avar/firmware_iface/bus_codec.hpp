#pragma once
// The protocol's half of a polled bus exchange (BusExchange): finds replies in received bytes
// and encodes the request that asks one device again. Implementations are pure and real-time
// safe (no I/O, no clock, no allocation, no exception); they may keep scratch space, so one
// instance serves one exchange engine.

#include <cstddef>
#include <cstdint>
#include <span>

namespace avar::firmware_iface {

/// One reply as the protocol decoded it.
struct BusReply {
  std::uint32_t device = 0;              ///< the replying device's bus address (servo ID, CAN node)
  std::uint8_t error = 0;                ///< the protocol's error or status byte, as sent
  bool device_error = false;             ///< the device reports an error (counted in device_errors)
  std::span<const std::uint8_t> params;  ///< payload; valid until the next parse()
};

enum class Framing {
  reply,         ///< a whole, valid reply (*used covers it)
  need_more,     ///< a reply may have started: *want more bytes are needed (at least 1)
  bad_checksum,  ///< a whole reply with a bad checksum (*used covers it): that reply is lost
  stray,         ///< *used bytes that cannot start a reply (noise; counted as framing errors)
  ignored,       ///< a well-formed packet that is no reply (an echo of a request; *used covers it)
};

class BusCodec {
 public:
  virtual ~BusCodec() = default;
  /// Looks for one reply at the start of `in`.
  virtual Framing parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used, std::size_t* want) noexcept = 0;
  /// Encodes into `out` the request that asks `device` alone for what the exchange asked every
  /// device (a retry); returns its size.
  virtual std::size_t encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept = 0;
};

/// A codec whose retry is a plain read of registers (smart servos' control tables).
class RegisterBusCodec : public BusCodec {
 public:
  /// What a retry reads: `length` bytes from `address`.
  void set_retry_read(std::uint16_t address, std::uint16_t length) noexcept {
    retry_address_ = address;
    retry_length_ = length;
  }

 protected:
  std::uint16_t retry_address_ = 0;
  std::uint16_t retry_length_ = 0;
};

}  // namespace avar::firmware_iface
