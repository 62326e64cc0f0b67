#pragma once
// Dense indices that name which table they index (channels, links...), where indices of
// different things meet in one record: an ActuatorSpec's channel cannot be passed where its link
// is meant. Real-time safe: a plain integer.

#include <compare>
#include <cstddef>

namespace avar {

template <class Tag>
struct Index {
  std::size_t value = 0;

  constexpr Index() = default;
  constexpr explicit Index(std::size_t v) : value(v) {}
  friend constexpr bool operator==(Index, Index) = default;
  friend constexpr auto operator<=>(Index, Index) = default;
};

}  // namespace avar
