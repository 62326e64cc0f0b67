// Smoothing filters: known responses (constants, sines well below and above the cutoff), zero
// phase (a peak stays where it was), and noise actually reduced.
#include "avar/playback/offline/smoothing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace avar::playback {
namespace {

constexpr double kRate = 200;  // Hz
constexpr double kCutoff = 5;  // Hz
constexpr std::array<SmoothingMethod, 4> kMethods = {SmoothingMethod::moving_average, SmoothingMethod::gaussian,
                                                     SmoothingMethod::bspline, SmoothingMethod::butterworth};

std::vector<double> sine(double hz, std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = std::sin(2 * M_PI * hz * static_cast<double>(i) / kRate);
  return x;
}

/// Largest |value| away from the ends (the middle 60%).
double middle_amplitude(const std::vector<double>& x) {
  double peak = 0;
  for (std::size_t i = x.size() / 5; i < x.size() * 4 / 5; ++i) peak = std::max(peak, std::abs(x[i]));
  return peak;
}

TEST(Smoothing, NamesRoundTrip) {
  for (auto m : {SmoothingMethod::none, SmoothingMethod::moving_average, SmoothingMethod::gaussian, SmoothingMethod::bspline,
                 SmoothingMethod::butterworth})
    EXPECT_EQ(smoothing_method_from_name(to_string(m)), m);
  EXPECT_FALSE(smoothing_method_from_name("median").has_value());
}

TEST(Smoothing, ConstantStaysConstantToTheEnds) {
  const std::vector<double> constant(700, 3.25);
  for (auto m : kMethods) {
    const auto y = smooth(constant, m, kRate, kCutoff);
    ASSERT_EQ(y.size(), constant.size());
    for (double v : y) ASSERT_NEAR(v, 3.25, 1e-9) << to_string(m);
  }
  EXPECT_NEAR(butterworth_zero_phase(constant, kRate, kCutoff, 2).back(), 3.25, 1e-9);
}

TEST(Smoothing, SineWellBelowCutoffPassesWithinOnePercent) {
  for (auto m : kMethods) {
    const auto y = smooth(sine(kCutoff / 10, 2000), m, kRate, kCutoff);
    EXPECT_NEAR(middle_amplitude(y), 1.0, 0.01) << to_string(m);
  }
  // The Butterworth filters pass a sine at a fifth of the cutoff within 1% too.
  for (int order : {2, 4}) EXPECT_NEAR(middle_amplitude(butterworth_zero_phase(sine(kCutoff / 5, 2000), kRate, kCutoff, order)), 1.0, 0.01);
}

TEST(Smoothing, SineAboveCutoffIsAttenuated) {
  for (auto m : kMethods) EXPECT_LT(middle_amplitude(smooth(sine(3 * kCutoff, 2000), m, kRate, kCutoff)), 0.3) << to_string(m);
  // Butterworth, forward and backward: |H|^2 = 1 / (1 + (f/fc)^(2 order)) (before warping).
  EXPECT_NEAR(middle_amplitude(butterworth_zero_phase(sine(3 * kCutoff, 4000), kRate, kCutoff, 2)), 1.0 / (1 + 81), 0.01);
  EXPECT_LT(middle_amplitude(butterworth_zero_phase(sine(3 * kCutoff, 4000), kRate, kCutoff, 4)), 1e-3);
  // At the cutoff the zero-phase filter gives half the amplitude (-6 dB).
  EXPECT_NEAR(middle_amplitude(butterworth_zero_phase(sine(kCutoff, 4000), kRate, kCutoff, 4)), 0.5, 0.01);
}

TEST(Smoothing, ZeroPhasePeakNotShifted) {
  std::vector<double> bump(801);
  for (std::size_t i = 0; i < bump.size(); ++i) {
    const double d = (static_cast<double>(i) - 400) / 30;
    bump[i] = std::exp(-0.5 * d * d);
  }
  for (auto m : kMethods) {
    const auto y = smooth(bump, m, kRate, kCutoff);
    const auto peak = std::max_element(y.begin(), y.end()) - y.begin();
    EXPECT_NEAR(static_cast<double>(peak), 400, 1) << to_string(m);
  }
}

TEST(Smoothing, NoiseIsReduced) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 0.1);
    const auto clean = sine(1, 2000);
    std::vector<double> noisy = clean;
    for (double& v : noisy) v += noise(rng);
    for (auto m : kMethods) {
      const auto y = smooth(noisy, m, kRate, kCutoff);
      double before = 0, after = 0;
      for (std::size_t i = 0; i < y.size(); ++i) {
        before += (noisy[i] - clean[i]) * (noisy[i] - clean[i]);
        after += (y[i] - clean[i]) * (y[i] - clean[i]);
      }
      EXPECT_LT(after, 0.25 * before) << to_string(m) << " seed " << seed;
    }
  }
}

TEST(Smoothing, RejectsBadParameters) {
  const std::vector<double> x(10, 1.0);
  EXPECT_THROW(smooth(x, SmoothingMethod::gaussian, kRate, 0), std::invalid_argument);
  EXPECT_THROW(smooth(x, SmoothingMethod::butterworth, kRate, kRate), std::invalid_argument);
  EXPECT_THROW(butterworth_zero_phase(x, kRate, kCutoff, 3), std::invalid_argument);
  EXPECT_EQ(smooth(x, SmoothingMethod::none, kRate, 0), x);
  EXPECT_TRUE(smooth(std::vector<double>{}, SmoothingMethod::moving_average, kRate, kCutoff).empty());
}

}  // namespace
}  // namespace avar::playback
