#pragma once
// Smoothing of a noisy sample sequence, offline (Parent, Computer Animation, 3.4): every filter
// takes samples evenly spaced in time and returns as many smoothed samples, without delay (all
// are centred or run forward and backward). Load-time/offline: allocates; not for the tick.
//
// Ends: the moving average and the Gaussian shrink their window to the samples that exist (a
// constant stays constant to the last sample); the B-spline is a least-squares fit over all
// samples; the Butterworth filter pads both ends with the signal mirrored about its end value
// (odd extension) and starts from the steady state of the first padded value.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace avar::playback {

enum class SmoothingMethod : std::uint8_t { none, moving_average, gaussian, bspline, butterworth };

/// "none", "moving_average", "gaussian", "bspline", "butterworth"; nullopt for anything else.
std::optional<SmoothingMethod> smoothing_method_from_name(std::string_view name);
const char* to_string(SmoothingMethod method);

/// Centred average over `half_width` samples either side (window 2 half_width + 1).
std::vector<double> moving_average(std::span<const double> samples, std::size_t half_width);

/// Centred Gaussian kernel of standard deviation `sigma_samples` (in samples, > 0), cut at 4 sigma
/// and normalised over the samples that exist.
std::vector<double> gaussian_smooth(std::span<const double> samples, double sigma_samples);

/// Least-squares uniform cubic B-spline approximation with control points every
/// `knot_spacing_samples` (>= 1) samples, evaluated at every sample. A tiny second-difference
/// penalty on the control points keeps spans without samples determined.
std::vector<double> bspline_smooth(std::span<const double> samples, double knot_spacing_samples);

/// Butterworth low-pass of `order` 2 or 4 (cascaded second-order sections from the bilinear
/// transform with the cutoff pre-warped), run forward then backward: zero phase, and the
/// magnitude response squared (-6 dB at the cutoff). cutoff_hz must lie in (0, sample_rate_hz/2).
std::vector<double> butterworth_zero_phase(std::span<const double> samples, double sample_rate_hz, double cutoff_hz,
                                           int order = 2);

/// One method at one cutoff frequency, with the parameters chosen so each filter's response falls
/// to half power near `cutoff_hz`: moving average half width round(0.443 fs / fc / 2), Gaussian
/// sigma = sqrt(ln 2) / (2 pi fc) s, B-spline knots every fs / (2 fc) samples, Butterworth order 4.
/// Throws std::invalid_argument when cutoff_hz is not in (0, sample_rate_hz / 2).
std::vector<double> smooth(std::span<const double> samples, SmoothingMethod method, double sample_rate_hz, double cutoff_hz);

}  // namespace avar::playback
