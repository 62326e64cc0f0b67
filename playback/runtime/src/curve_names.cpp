// The names of the curve vocabulary, as show files spell them.
#include <array>
#include <string_view>
#include <utility>
#include <vector>

#include "avar/playback/runtime/curve.hpp"

namespace avar::playback {
namespace {

template <typename E, std::size_t N>
std::optional<E> lookup(const std::array<std::pair<std::string_view, E>, N>& table, std::string_view name) {
  for (const auto& [n, e] : table)
    if (n == name) return e;
  return std::nullopt;
}
template <typename E, std::size_t N>
std::vector<std::string_view> names_in(const std::array<std::pair<std::string_view, E>, N>& table) {
  std::vector<std::string_view> names;
  names.reserve(N);
  for (const auto& entry : table) names.push_back(entry.first);
  return names;
}
template <typename E, std::size_t N>
const char* name_of(const std::array<std::pair<std::string_view, E>, N>& table, E e) {
  for (const auto& [n, v] : table)
    if (v == e) return n.data();
  return table[0].first.data();
}

using I = Interpolation;
constexpr std::array<std::pair<std::string_view, I>, 18> kInterpolations{{
    {"constant", I::step},
    {"linear", I::linear},
    {"bezier", I::bezier},
    {"sine", I::sine},
    {"quad", I::quad},
    {"cubic", I::cubic},
    {"quart", I::quart},
    {"quint", I::quint},
    {"expo", I::expo},
    {"circ", I::circ},
    {"back", I::back},
    {"bounce", I::bounce},
    {"elastic", I::elastic},
    {"hermite", I::hermite},
    {"catmull_rom", I::catmull_rom},
    {"cardinal", I::cardinal},
    {"kochanek_bartels", I::kochanek_bartels},
    {"bspline", I::bspline},
}};
constexpr std::array<std::pair<std::string_view, Easing>, 4> kEasings{{
    {"auto", Easing::automatic},
    {"ease_in", Easing::ease_in},
    {"ease_out", Easing::ease_out},
    {"ease_in_out", Easing::ease_in_out},
}};
constexpr std::array<std::pair<std::string_view, HandleType>, 5> kHandleTypes{{
    {"free", HandleType::free},
    {"aligned", HandleType::aligned},
    {"vector", HandleType::vector},
    {"auto", HandleType::automatic},
    {"auto_clamped", HandleType::auto_clamped},
}};
constexpr std::array<std::pair<std::string_view, Extrapolation>, 2> kExtrapolations{{
    {"constant", Extrapolation::constant},
    {"linear", Extrapolation::linear},
}};
constexpr std::array<std::pair<std::string_view, AutoSmoothing>, 2> kSmoothings{{
    {"none", AutoSmoothing::none},
    {"continuous_acceleration", AutoSmoothing::continuous_acceleration},
}};
constexpr std::array<std::pair<std::string_view, CycleMode>, 4> kCycleModes{{
    {"none", CycleMode::none},
    {"repeat", CycleMode::repeat},
    {"repeat_offset", CycleMode::repeat_offset},
    {"mirror", CycleMode::mirror},
}};

}  // namespace

std::optional<Interpolation> interpolation_from_name(std::string_view name) {
  if (name == "step") return Interpolation::step;  // avar's older name for Blender's constant
  return lookup(kInterpolations, name);
}
std::optional<Easing> easing_from_name(std::string_view name) { return lookup(kEasings, name); }
std::optional<HandleType> handle_type_from_name(std::string_view name) { return lookup(kHandleTypes, name); }
std::optional<Extrapolation> extrapolation_from_name(std::string_view name) { return lookup(kExtrapolations, name); }
std::optional<AutoSmoothing> auto_smoothing_from_name(std::string_view name) { return lookup(kSmoothings, name); }
std::optional<CycleMode> cycle_mode_from_name(std::string_view name) { return lookup(kCycleModes, name); }

const char* to_string(Interpolation interpolation) { return name_of(kInterpolations, interpolation); }
const char* to_string(Easing easing) { return name_of(kEasings, easing); }
const char* to_string(HandleType type) { return name_of(kHandleTypes, type); }
const char* to_string(Extrapolation extrapolation) { return name_of(kExtrapolations, extrapolation); }
const char* to_string(AutoSmoothing smoothing) { return name_of(kSmoothings, smoothing); }
const char* to_string(CycleMode mode) { return name_of(kCycleModes, mode); }

const char* interpolation_names() {
  return "constant (or step), linear, bezier, sine, quad, cubic, quart, quint, expo, circ, back, bounce, elastic, hermite, "
         "catmull_rom, cardinal, kochanek_bartels, bspline";
}

std::vector<std::string_view> interpolation_name_list() { return names_in(kInterpolations); }
std::vector<std::string_view> easing_name_list() { return names_in(kEasings); }
std::vector<std::string_view> handle_type_name_list() { return names_in(kHandleTypes); }
std::vector<std::string_view> extrapolation_name_list() { return names_in(kExtrapolations); }

bool is_easing_family(Interpolation i) { return i >= Interpolation::sine && i <= Interpolation::elastic; }

}  // namespace avar::playback
