#pragma once
// Well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF), for
// readers that hand text to a parser that trusts it (TinyXML steps over a multi-byte sequence by
// its lead byte, past the end of a truncated one).

#include <cstddef>
#include <optional>
#include <string_view>

namespace avar {

/// The offset of the first byte that does not begin or continue a well-formed sequence, or
/// nothing when the whole text is well-formed.
std::optional<std::size_t> first_invalid_utf8(std::string_view text) noexcept;

}  // namespace avar
