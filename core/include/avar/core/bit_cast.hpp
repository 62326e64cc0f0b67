#pragma once
// std::bit_cast where the standard library has it, and the same by memcpy where it does not
// (emscripten 3.1.6's libc++, which builds the curve engine for the studio page).

#include <cstdint>
#include <cstring>
#include <type_traits>
#if __has_include(<bit>)
#include <bit>
#endif

namespace avar {

template <typename To, typename From>
To bit_cast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>);
#if defined(__cpp_lib_bit_cast)
  return std::bit_cast<To>(from);
#else
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
#endif
}

/// Whether two doubles are the same bits (0.0 and -0.0 differ; a NaN is itself): "the same
/// number" for results that must be bit-identical.
inline bool same_bits(double a, double b) noexcept { return bit_cast<std::uint64_t>(a) == bit_cast<std::uint64_t>(b); }

}  // namespace avar
