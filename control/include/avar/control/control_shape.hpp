#pragma once
// How a control's normalised value is shaped before it drives a channel: an optional input
// range, inversion, a dead zone, an expo curve. Pure functions; real-time safe.

#include <optional>
#include <utility>

namespace avar::control {

struct ControlShape {
  /// Raw values from `first` to `second` span the control (a unipolar 0..1 after this); unset:
  /// the control's own normalised range (bipolar -1..1 or unipolar 0..1). first != second.
  std::optional<std::pair<double, double>> input;
  bool invert = false;     ///< bipolar: -x; unipolar: 1 - x
  double dead_zone = 0;    ///< 0..<1: |x| (bipolar) or x (unipolar) below it reads 0, the rest rescaled
  double expo = 0;         ///< 0..1: mix of linear (0) and cubic (1) response, finer near rest
  double smoothing_s = 0;  ///< time constant of a first-order low-pass (applied by the caller), s
};

struct ShapedValue {
  double value = 0;  ///< clamped to -1..1 (bipolar) or 0..1 (unipolar)
  bool bipolar = false;
};

/// The shaped value of a raw reading; a non-finite raw value reads as rest (0).
ShapedValue shape_control(double raw, bool bipolar, const ControlShape& shape) noexcept;

}  // namespace avar::control
