#pragma once
// Status codes returned on the real-time path (the tick and everything it calls), where
// exceptions are not used. Real-time safe: plain enums and constexpr lookups.

#include <string_view>

namespace avar {

/// [[nodiscard]]: a status dropped on the floor is a fault nobody handles.
// clang-format 14 misreads an attribute on an enum and indents it:
// clang-format off
enum class [[nodiscard]] Status {
  ok,
  timeout,       ///< a deadline passed before the operation completed
  io_error,      ///< the transport failed (port closed, write error, device gone)
  bad_data,      ///< bytes arrived but did not decode (framing, checksum, range)
  not_finite,    ///< a NaN or infinity reached a stage that refuses it
  out_of_range,  ///< a value outside what the receiver accepts
};
// clang-format on

constexpr std::string_view to_string(Status s) noexcept {
  switch (s) {
    case Status::ok: return "ok";
    case Status::timeout: return "timeout";
    case Status::io_error: return "I/O error";
    case Status::bad_data: return "bad data";
    case Status::not_finite: return "non-finite value";
    case Status::out_of_range: return "out of range";
  }
  return "unknown";
}

}  // namespace avar
