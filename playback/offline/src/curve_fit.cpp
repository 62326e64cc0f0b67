#include "avar/playback/offline/curve_fit.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace avar::playback {
namespace {

/// The keys being fitted: sample indices, corner flags, and their solved slopes.
struct Keys {
  std::vector<std::size_t> sample;
  std::vector<bool> corner;
  std::vector<double> in_slope, out_slope;  ///< units per second
};

void check_input(std::span<const double> times, std::span<const double> values, const CurveFitOptions& options) {
  if (times.size() != values.size()) throw std::invalid_argument("curve fit: expected as many values as times");
  if (times.empty()) throw std::invalid_argument("curve fit: expected at least one sample");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw std::invalid_argument("curve fit: expected a tolerance above 0");
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || !std::isfinite(values[i])) throw std::invalid_argument("curve fit: samples must be finite");
    if (i > 0 && !(times[i] > times[i - 1])) throw std::invalid_argument("curve fit: times must strictly increase");
  }
}

double chord_slope(std::span<const double> t, std::span<const double> v, std::size_t a, std::size_t b) {
  return (v[b] - v[a]) / (t[b] - t[a]);
}

/// Least-squares slopes for the keys (values fixed at their samples). Slot layout: each key has
/// one slope slot, corners two (in, out).
void solve_slopes(std::span<const double> t, std::span<const double> v, Keys& keys) {
  const std::size_t count = keys.sample.size();
  std::vector<Eigen::Index> in_slot(count), out_slot(count);
  Eigen::Index slots = 0;
  for (std::size_t k = 0; k < count; ++k) {
    in_slot[k] = slots;
    if (keys.corner[k]) ++slots;
    out_slot[k] = slots++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(slots);
  std::vector<double> reference(static_cast<std::size_t>(slots), 0.0), scale(static_cast<std::size_t>(slots), 0.0);
  for (std::size_t k = 0; k + 1 < count; ++k) {
    const std::size_t a = keys.sample[k], b = keys.sample[k + 1];
    const double t0 = t[a], duration = t[b] - t0, v0 = v[a], v1 = v[b];
    const Eigen::Index p = out_slot[k], q = in_slot[k + 1];
    double pp = 0, pq = 0, qq = 0, rp = 0, rq = 0;
    for (std::size_t j = a + 1; j < b; ++j) {
      const double s = (t[j] - t0) / duration, s2 = s * s, s3 = s2 * s;
      const double cp = duration * (s3 - 2 * s2 + s), cq = duration * (s3 - s2);
      const double r = v[j] - (2 * s3 - 3 * s2 + 1) * v0 - (-2 * s3 + 3 * s2) * v1;
      pp += cp * cp, pq += cp * cq, qq += cq * cq, rp += cp * r, rq += cq * r;
    }
    entries.emplace_back(p, p, pp);
    entries.emplace_back(p, q, pq);
    entries.emplace_back(q, p, pq);
    entries.emplace_back(q, q, qq);
    rhs[p] += rp;
    rhs[q] += rq;
    // Reference slopes for the tiny regularisation: the chord of each side.
    const double chord = (v1 - v0) / duration;
    reference[static_cast<std::size_t>(p)] += chord * duration, scale[static_cast<std::size_t>(p)] += duration;
    reference[static_cast<std::size_t>(q)] += chord * duration, scale[static_cast<std::size_t>(q)] += duration;
  }
  // A slope no sample constrains (a segment without interior samples) falls back to the mean
  // of its chords; elsewhere the weight is negligible against the samples.
  for (Eigen::Index s = 0; s < slots; ++s) {
    const auto i = static_cast<std::size_t>(s);
    const double mean_duration = scale[i] > 0 ? scale[i] : 1;
    const double weight = 1e-9 * mean_duration * mean_duration;
    entries.emplace_back(s, s, weight);
    rhs[s] += weight * (scale[i] > 0 ? reference[i] / scale[i] : 0.0);
  }
  Eigen::SparseMatrix<double> normal(slots, slots);
  normal.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  const Eigen::VectorXd slope = solver.solve(rhs);
  keys.in_slope.assign(count, 0.0);
  keys.out_slope.assign(count, 0.0);
  for (std::size_t k = 0; k < count; ++k) {
    keys.in_slope[k] = slope[in_slot[k]];
    keys.out_slope[k] = slope[out_slot[k]];
  }
}

RawCurve to_raw_curve(std::span<const double> t, std::span<const double> v, const Keys& keys, const SourceLocation& where) {
  RawCurve raw;
  raw.where = where;
  const std::size_t count = keys.sample.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = keys.sample[k];
    RawKey key;
    key.time = t[i];
    key.value = v[i];
    key.interpolation = Interpolation::bezier;
    key.where = where;
    // Handles a third of the neighbouring segment away in time; the end keys mirror their one
    // handle (it shapes nothing under constant extrapolation, but keeps both sides free).
    const double before =
        k > 0 ? (t[i] - t[keys.sample[k - 1]]) / 3 : (t[keys.sample[std::min<std::size_t>(1, count - 1)]] - t[i]) / 3;
    const double after = k + 1 < count ? (t[keys.sample[k + 1]] - t[i]) / 3 : before;
    if (count > 1) {
      key.left = Handle{t[i] - before, v[i] - keys.in_slope[k] * before};
      key.right = Handle{t[i] + after, v[i] + keys.out_slope[k] * after};
    }
    raw.keys.push_back(key);
  }
  return raw;
}

/// For every segment whose worst |error| exceeds `limit`, the sample where it is worst.
template <typename Evaluate>
std::vector<std::size_t> worst_over(std::span<const double> v, const Keys& keys, double limit, Evaluate evaluate,
                                    double& max_error) {
  std::vector<std::size_t> splits;
  max_error = 0;
  for (std::size_t k = 0; k + 1 < keys.sample.size(); ++k) {
    double worst = 0;
    std::size_t at = 0;
    for (std::size_t j = keys.sample[k]; j <= keys.sample[k + 1]; ++j) {
      const double e = std::abs(evaluate(k, j) - v[j]);
      if (e > worst) worst = e, at = j;
    }
    max_error = std::max(max_error, worst);
    if (worst > limit && at > keys.sample[k] && at < keys.sample[k + 1]) splits.push_back(at);
  }
  return splits;
}

void insert_keys(Keys& keys, const std::vector<std::size_t>& splits) {
  for (std::size_t s : splits) {
    const auto it = std::lower_bound(keys.sample.begin(), keys.sample.end(), s);
    const auto pos = it - keys.sample.begin();
    keys.sample.insert(it, s);
    keys.corner.insert(keys.corner.begin() + pos, false);
  }
}

double hermite_at(std::span<const double> t, std::span<const double> v, const Keys& keys, std::size_t k, std::size_t j) {
  const std::size_t a = keys.sample[k], b = keys.sample[k + 1];
  const double duration = t[b] - t[a], s = (t[j] - t[a]) / duration, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * v[a] + duration * (s3 - 2 * s2 + s) * keys.out_slope[k] + (-2 * s3 + 3 * s2) * v[b] +
         duration * (s3 - s2) * keys.in_slope[k + 1];
}

/// Solves the slopes of `keys`; when the Hermite pieces are within the tolerance, builds the
/// curve into `result` and checks it as playback evaluates it. Returns the samples to split at
/// (one per segment over the tolerance), empty when `result` holds a curve within it.
std::vector<std::size_t> over_tolerance(std::span<const double> t, std::span<const double> v, Keys& keys, double tolerance,
                                        const SourceLocation& where, CurveFitResult& result) {
  keys.in_slope.assign(keys.sample.size(), 0.0);
  keys.out_slope.assign(keys.sample.size(), 0.0);
  if (keys.sample.size() > 1) solve_slopes(t, v, keys);
  // Aim a hair inside the tolerance with the pieces, then check the curve that will play.
  double error = 0;
  auto splits = worst_over(
      v, keys, tolerance * (1 - 1e-6), [&](std::size_t k, std::size_t j) { return hermite_at(t, v, keys, k, j); }, error);
  if (!splits.empty()) return splits;
  result.curve = to_raw_curve(t, v, keys, where);
  const Curve built = Curve::build(result.curve);
  return worst_over(
      v, keys, tolerance, [&](std::size_t, std::size_t j) { return built.evaluate(t[j]); }, result.max_error);
}

}  // namespace

std::vector<std::size_t> find_corners(std::span<const double> t, std::span<const double> v, const CurveFitOptions& options) {
  std::vector<std::size_t> corners;
  const std::size_t n = t.size();
  if (n < 3) return corners;
  const auto [low, high] = std::minmax_element(v.begin(), v.end());
  const double range = *high - *low;
  if (!(range > 0)) return corners;
  const double aspect = (t[n - 1] - t[0]) / range;  // scales slopes into the square box
  const double threshold = options.corner_angle_deg * std::numbers::pi / 180;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double left = chord_slope(t, v, i - 1, i), right = chord_slope(t, v, i, i + 1);
    const double turn = std::abs(std::atan(right * aspect) - std::atan(left * aspect));
    const double shorter = std::min(t[i] - t[i - 1], t[i + 1] - t[i]);
    if (turn > threshold && std::abs(right - left) * shorter > 4 * options.tolerance) corners.push_back(i);
  }
  return corners;
}

CurveFitResult fit_curve(std::span<const double> t, std::span<const double> v, const CurveFitOptions& options,
                         const SourceLocation& where) {
  check_input(t, v, options);
  CurveFitResult result;
  const std::size_t n = t.size();
  Keys keys;
  keys.sample.push_back(0);
  keys.corner.push_back(false);
  if (options.keep_corners) result.corners = find_corners(t, v, options);
  for (std::size_t c : result.corners) {
    keys.sample.push_back(c);
    keys.corner.push_back(true);
  }
  if (n > 1) {
    keys.sample.push_back(n - 1);
    keys.corner.push_back(false);
  }
  // Split until within the tolerance, then drop every key the others can do without.
  for (;;) {
    const auto splits = over_tolerance(t, v, keys, options.tolerance, where, result);
    if (splits.empty()) break;
    insert_keys(keys, splits);
  }
  for (std::size_t k = 1; k + 1 < keys.sample.size();) {
    if (keys.corner[k]) {
      ++k;
      continue;
    }
    Keys fewer = keys;
    fewer.sample.erase(fewer.sample.begin() + static_cast<std::ptrdiff_t>(k));
    fewer.corner.erase(fewer.corner.begin() + static_cast<std::ptrdiff_t>(k));
    CurveFitResult attempt;
    if (over_tolerance(t, v, fewer, options.tolerance, where, attempt).empty()) {
      keys = std::move(fewer);
      result.curve = std::move(attempt.curve);
      result.max_error = attempt.max_error;
    } else {
      ++k;
    }
  }
  result.key_samples = keys.sample;
  return result;
}

}  // namespace avar::playback
