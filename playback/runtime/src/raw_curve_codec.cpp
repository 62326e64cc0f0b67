#include "avar/playback/runtime/raw_curve_codec.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace avar::playback {
namespace {

template <typename E>
double code(E e) {
  return static_cast<double>(static_cast<int>(e));
}

/// Reads the flat array in order, naming each field in its errors.
class Reader {
 public:
  explicit Reader(std::span<const double> flat) : flat_(flat) {}
  double number(const char* what) {
    if (at_ >= flat_.size()) throw std::invalid_argument(std::string("flat curve: ends before ") + what);
    return flat_[at_++];
  }
  int whole(const char* what, int low, int high) {
    const double v = number(what);
    if (!(v >= low && v <= high) || v != std::floor(v))
      throw std::invalid_argument(std::string("flat curve: ") + what + " must be a whole number from " + std::to_string(low) +
                                  " to " + std::to_string(high));
    return static_cast<int>(v);
  }
  bool flag(const char* what) { return whole(what, 0, 1) == 1; }
  template <typename E>
  E enumeration(const char* what, E last) {
    return static_cast<E>(whole(what, 0, static_cast<int>(last)));
  }
  std::size_t left() const { return flat_.size() - at_; }

 private:
  std::span<const double> flat_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<double> encode_raw_curve(const RawCurve& curve) {
  std::vector<double> flat = {kRawCurveFormat,
                              static_cast<double>(curve.keys.size()),
                              code(curve.extrapolation),
                              code(curve.auto_smoothing),
                              code(curve.cycles.before),
                              code(curve.cycles.after),
                              static_cast<double>(curve.cycles.before_count),
                              static_cast<double>(curve.cycles.after_count)};
  flat.reserve(kRawCurveHeaderFields + curve.keys.size() * kRawCurveKeyFields);
  for (const RawKey& k : curve.keys) {
    flat.insert(flat.end(), {k.time, k.value, code(k.interpolation), code(k.easing), k.back, k.amplitude, k.period});
    for (const auto& [handle, type] : {std::pair{&k.left, &k.left_type}, std::pair{&k.right, &k.right_type}}) {
      flat.insert(flat.end(), {handle->has_value() ? 1.0 : 0.0, handle->has_value() ? (*handle)->time : 0.0,
                               handle->has_value() ? (*handle)->value : 0.0, type->has_value() ? code(**type) : -1.0});
    }
    for (const std::optional<double>* slope : {&k.in_slope, &k.out_slope})
      flat.insert(flat.end(), {slope->has_value() ? 1.0 : 0.0, slope->value_or(0.0)});
    flat.insert(flat.end(), {k.tension, k.continuity, k.bias});
  }
  return flat;
}

RawCurve decode_raw_curve(std::span<const double> flat) {
  Reader r(flat);
  if (r.number("the format") != kRawCurveFormat) throw std::invalid_argument("flat curve: not format 1");
  const int count = r.whole("the key count", 0, 1 << 30);
  RawCurve curve;
  curve.extrapolation = r.enumeration("the extrapolation", Extrapolation::linear);
  curve.auto_smoothing = r.enumeration("the auto smoothing", AutoSmoothing::continuous_acceleration);
  curve.cycles.before = r.enumeration("the cycles before", CycleMode::mirror);
  curve.cycles.after = r.enumeration("the cycles after", CycleMode::mirror);
  curve.cycles.before_count = r.whole("the cycle count before", 0, 1 << 30);
  curve.cycles.after_count = r.whole("the cycle count after", 0, 1 << 30);
  if (r.left() != static_cast<std::size_t>(count) * kRawCurveKeyFields)
    throw std::invalid_argument("flat curve: " + std::to_string(count) + " keys need " +
                                std::to_string(static_cast<std::size_t>(count) * kRawCurveKeyFields) +
                                " numbers after the header, found " + std::to_string(r.left()));
  curve.keys.resize(static_cast<std::size_t>(count));
  for (RawKey& k : curve.keys) {
    k.time = r.number("a key's time");
    k.value = r.number("a key's value");
    k.interpolation = r.enumeration("a key's interpolation", Interpolation::bspline);
    k.easing = r.enumeration("a key's easing", Easing::ease_in_out);
    k.back = r.number("a key's back");
    k.amplitude = r.number("a key's amplitude");
    k.period = r.number("a key's period");
    for (auto [handle, type] : {std::pair{&k.left, &k.left_type}, std::pair{&k.right, &k.right_type}}) {
      const bool present = r.flag("a handle's presence");
      const double time = r.number("a handle's time");
      const double value = r.number("a handle's value");
      const int kind = r.whole("a handle's type", -1, static_cast<int>(HandleType::auto_clamped));
      if (present) *handle = Handle{time, value};
      if (kind >= 0) *type = static_cast<HandleType>(kind);
    }
    for (std::optional<double>* slope : {&k.in_slope, &k.out_slope}) {
      const bool present = r.flag("a slope's presence");
      const double value = r.number("a slope");
      if (present) *slope = value;
    }
    k.tension = r.number("a key's tension");
    k.continuity = r.number("a key's continuity");
    k.bias = r.number("a key's bias");
  }
  return curve;
}

}  // namespace avar::playback
