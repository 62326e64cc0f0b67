#pragma once
// Helpers shared by the fuzz targets: the input as text, and a reader that takes small values
// off the front of the input (a selector, a length) and leaves the rest as payload.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace avar::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Takes bytes off the front of the fuzzer's input; past the end every value reads as 0.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : bytes_(data, size) {}

  std::uint8_t u8() noexcept { return bytes_.empty() ? 0 : take(1)[0]; }
  std::uint16_t u16() noexcept { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint32_t u32() noexcept { return static_cast<std::uint32_t>(u16() | (std::uint32_t{u16()} << 16)); }
  bool flag() noexcept { return (u8() & 1) != 0; }
  /// Up to `n` bytes (fewer at the end of the input).
  std::span<const std::uint8_t> take(std::size_t n) noexcept {
    const std::span<const std::uint8_t> head = bytes_.first(n < bytes_.size() ? n : bytes_.size());
    bytes_ = bytes_.subspan(head.size());
    return head;
  }
  std::span<const std::uint8_t> rest() noexcept { return take(bytes_.size()); }
  bool empty() const noexcept { return bytes_.empty(); }

 private:
  std::span<const std::uint8_t> bytes_;
};

}  // namespace avar::fuzz
