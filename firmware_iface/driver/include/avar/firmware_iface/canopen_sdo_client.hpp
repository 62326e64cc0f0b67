#pragma once
// Blocking expedited SDO transfers to one CANopen node, for bringing drives up (start,
// read_positions): send the request on 0x600 + node, wait on the transport's clock for the
// server's answer on 0x580 + node with the same index and sub-index. Frames that do not answer
// are dropped. A transfer nobody answers is aborted towards the server (0x05040000), as CiA 301
// asks of a client that gives up. Not real-time.

#include <chrono>
#include <cstdint>
#include <string>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/frame_transport.hpp"

namespace avar::firmware_iface::canopen {

struct SdoOutcome {
  /// ok; out_of_range when the server aborted (abort_code says why); timeout when no answer
  /// came; io_error when the bus failed.
  Status status = Status::ok;
  std::uint32_t abort_code = 0;
  std::uint32_t value = 0;  ///< upload: the value read (size bytes, zero-extended)
  std::uint8_t size = 0;    ///< upload: bytes the server sent (0 = size not indicated)
};

/// Writes `size` (1..4) bytes of `value` to index:sub of `node`.
SdoOutcome sdo_download(FrameTransport& bus, std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                        std::uint8_t size, std::chrono::nanoseconds timeout);
/// Reads index:sub of `node`.
SdoOutcome sdo_upload(FrameTransport& bus, std::uint8_t node, std::uint16_t index, std::uint8_t sub,
                      std::chrono::nanoseconds timeout);

/// What went wrong, for messages: "SDO abort 0x06090030 (value range exceeded)
/// writing 0x6060:00", "no SDO answer reading 0x6064:00 (timeout)".
std::string describe_sdo_failure(const SdoOutcome& outcome, bool writing, std::uint16_t index, std::uint8_t sub);

}  // namespace avar::firmware_iface::canopen
