#include "avar/playback/offline/smoothing.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace avar::playback {
namespace {

struct NamedMethod {
  SmoothingMethod method;
  const char* name;
};
constexpr std::array<NamedMethod, 5> kMethods = {{{SmoothingMethod::none, "none"},
                                                  {SmoothingMethod::moving_average, "moving_average"},
                                                  {SmoothingMethod::gaussian, "gaussian"},
                                                  {SmoothingMethod::bspline, "bspline"},
                                                  {SmoothingMethod::butterworth, "butterworth"}}};

/// A centred kernel (weights[0] at the centre, weights[k] at +-k), renormalised at the ends.
std::vector<double> convolve_symmetric(std::span<const double> x, const std::vector<double>& weights) {
  const std::size_t n = x.size(), radius = weights.size() - 1;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    double sum = weights[0] * x[i], total = weights[0];
    for (std::size_t k = 1; k <= radius; ++k) {
      if (i >= k) sum += weights[k] * x[i - k], total += weights[k];
      if (i + k < n) sum += weights[k] * x[i + k], total += weights[k];
    }
    y[i] = sum / total;
  }
  return y;
}

/// Uniform cubic B-spline basis weights at local coordinate w in [0, 1).
std::array<double, 4> bspline_basis(double w) {
  const double w2 = w * w, w3 = w2 * w, v = 1 - w;
  return {v * v * v / 6, (3 * w3 - 6 * w2 + 4) / 6, (-3 * w3 + 3 * w2 + 3 * w + 1) / 6, w3 / 6};
}

/// One second-order low-pass section, transposed direct form II.
struct Biquad {
  double b0, b1, b2, a1, a2;
  double z1 = 0, z2 = 0;
  void settle(double x) {  // steady state for a constant input x (unit DC gain)
    z2 = (b2 - a2) * x;
    z1 = (1 - b0) * x;
  }
  double step(double x) {
    const double y = b0 * x + z1;
    z1 = b1 * x - a1 * y + z2;
    z2 = b2 * x - a2 * y;
    return y;
  }
};

std::vector<Biquad> butterworth_sections(double fs, double fc, int order) {
  const double k = std::tan(std::numbers::pi * fc / fs);
  std::vector<Biquad> sections;
  // Poles of the analogue Butterworth prototype in conjugate pairs: Q = 1 / (2 cos(theta)).
  for (int p = 0; p < order / 2; ++p) {
    const double theta = std::numbers::pi * (2 * p + 1) / (2.0 * order);
    const double q = 1 / (2 * std::cos(theta));
    const double norm = 1 / (1 + k / q + k * k);
    const double b0 = k * k * norm;
    sections.push_back({b0, 2 * b0, b0, 2 * (k * k - 1) * norm, (1 - k / q + k * k) * norm});
  }
  return sections;
}

void run_sections(std::vector<double>& x, std::vector<Biquad> sections) {
  for (Biquad& s : sections) {
    s.settle(x.front());
    for (double& v : x) v = s.step(v);
  }
}

}  // namespace

std::optional<SmoothingMethod> smoothing_method_from_name(std::string_view name) {
  for (const auto& m : kMethods)
    if (name == m.name) return m.method;
  return std::nullopt;
}

const char* to_string(SmoothingMethod method) { return kMethods[static_cast<std::size_t>(method)].name; }

std::vector<double> moving_average(std::span<const double> samples, std::size_t half_width) {
  if (samples.empty()) return {};
  return convolve_symmetric(samples, std::vector<double>(half_width + 1, 1.0));
}

std::vector<double> gaussian_smooth(std::span<const double> samples, double sigma_samples) {
  if (!(sigma_samples > 0)) throw std::invalid_argument("gaussian smoothing: sigma must be above 0 samples");
  if (samples.empty()) return {};
  const auto radius = static_cast<std::size_t>(std::ceil(4 * sigma_samples));
  std::vector<double> weights(radius + 1);
  for (std::size_t k = 0; k <= radius; ++k) {
    const double d = static_cast<double>(k) / sigma_samples;
    weights[k] = std::exp(-0.5 * d * d);
  }
  return convolve_symmetric(samples, weights);
}

std::vector<double> bspline_smooth(std::span<const double> samples, double knot_spacing_samples) {
  if (!(knot_spacing_samples >= 1)) throw std::invalid_argument("bspline smoothing: knot spacing must be at least 1 sample");
  const std::size_t n = samples.size();
  if (n < 2) return {samples.begin(), samples.end()};
  // Spans of the uniform spline cover [0, n - 1] in sample units; control points = spans + 3.
  const auto spans = static_cast<std::size_t>(std::max(1.0, std::ceil(static_cast<double>(n - 1) / knot_spacing_samples)));
  const double span_length = static_cast<double>(n - 1) / static_cast<double>(spans);
  const auto controls = static_cast<Eigen::Index>(spans + 3);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(controls);
  auto locate = [&](std::size_t i, std::size_t& span, double& w) {
    const double x = static_cast<double>(i) / span_length;
    span = std::min(static_cast<std::size_t>(x), spans - 1);
    w = x - static_cast<double>(span);
  };
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t span = 0;
    double w = 0;
    locate(i, span, w);
    const auto basis = bspline_basis(w);
    for (std::size_t a = 0; a < 4; ++a) {
      const auto ra = static_cast<Eigen::Index>(span + a);
      rhs[ra] += basis[a] * samples[i];
      for (std::size_t b = 0; b < 4; ++b) entries.emplace_back(ra, static_cast<Eigen::Index>(span + b), basis[a] * basis[b]);
    }
  }
  const double penalty = 1e-8;
  for (Eigen::Index c = 0; c + 2 < controls; ++c) {
    const std::array<double, 3> d = {1, -2, 1};
    for (Eigen::Index a = 0; a < 3; ++a)
      for (Eigen::Index b = 0; b < 3; ++b)
        entries.emplace_back(c + a, c + b, penalty * d[static_cast<std::size_t>(a)] * d[static_cast<std::size_t>(b)]);
  }
  Eigen::SparseMatrix<double> normal(controls, controls);
  normal.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  const Eigen::VectorXd control = solver.solve(rhs);
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t span = 0;
    double w = 0;
    locate(i, span, w);
    const auto basis = bspline_basis(w);
    double v = 0;
    for (std::size_t a = 0; a < 4; ++a) v += basis[a] * control[static_cast<Eigen::Index>(span + a)];
    y[i] = v;
  }
  return y;
}

std::vector<double> butterworth_zero_phase(std::span<const double> samples, double sample_rate_hz, double cutoff_hz, int order) {
  const double fs = sample_rate_hz;
  const double fc = cutoff_hz;
  if (order != 2 && order != 4) throw std::invalid_argument("butterworth: order must be 2 or 4");
  if (!(fs > 0) || !(fc > 0) || !(fc < 0.5 * fs))
    throw std::invalid_argument("butterworth: cutoff must lie between 0 and half the sample rate");
  const std::size_t n = samples.size();
  if (n < 2) return {samples.begin(), samples.end()};
  // Pad with the odd extension, long enough for the start-up transient to die out.
  const std::size_t pad = std::min(n - 1, static_cast<std::size_t>(std::ceil(6 * fs / fc)) + 3);
  std::vector<double> x;
  x.reserve(n + 2 * pad);
  for (std::size_t k = pad; k >= 1; --k) x.push_back(2 * samples[0] - samples[k]);
  x.insert(x.end(), samples.begin(), samples.end());
  for (std::size_t k = 1; k <= pad; ++k) x.push_back(2 * samples[n - 1] - samples[n - 1 - k]);
  const auto sections = butterworth_sections(fs, fc, order);
  run_sections(x, sections);
  std::reverse(x.begin(), x.end());
  run_sections(x, sections);
  std::reverse(x.begin(), x.end());
  return {x.begin() + static_cast<std::ptrdiff_t>(pad), x.begin() + static_cast<std::ptrdiff_t>(pad + n)};
}

std::vector<double> smooth(std::span<const double> samples, SmoothingMethod method, double sample_rate_hz, double cutoff_hz) {
  const double fs = sample_rate_hz;
  const double fc = cutoff_hz;
  if (method == SmoothingMethod::none) return {samples.begin(), samples.end()};
  if (!(fs > 0) || !(fc > 0) || !(fc < 0.5 * fs))
    throw std::invalid_argument("smoothing: the cutoff must lie between 0 and half the sample rate");
  switch (method) {
    case SmoothingMethod::moving_average:
      return moving_average(samples, static_cast<std::size_t>(std::lround(0.443 * fs / fc / 2)));
    case SmoothingMethod::gaussian: return gaussian_smooth(samples, std::sqrt(std::log(2.0)) / (2 * std::numbers::pi * fc) * fs);
    case SmoothingMethod::bspline: return bspline_smooth(samples, std::max(1.0, fs / (2 * fc)));
    case SmoothingMethod::butterworth: return butterworth_zero_phase(samples, fs, fc, 4);
    case SmoothingMethod::none: break;
  }
  return {samples.begin(), samples.end()};
}

}  // namespace avar::playback
