// avar's curve engine for the studio page, compiled to WebAssembly (cmake/AvarWasm.cmake): the
// same sources as the native build (Curve::build and Curve::evaluate), so that for the same keys
// and time the page shows exactly what the figure will do. Keys come in flat
// (playback/runtime/raw_curve_codec.hpp); the page passes arrays through the module's heap.
//
// A C interface, for cwrap: curves are numbered; a failed build returns -1 and avar_error()
// says why, in the show reader's words. Single-threaded, like the page.

#include <cstddef>
#include <exception>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "avar/playback/offline/handles.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/raw_curve_codec.hpp"

namespace {

/// A built curve and the keys it was built from (what a rebuild reuses segments of).
struct Built {
  avar::playback::Curve curve;
  avar::playback::RawCurve raw;
};

std::vector<std::unique_ptr<Built>> curves;
std::string last_error;

const avar::playback::Curve* find(int id) {
  if (id < 0 || static_cast<std::size_t>(id) >= curves.size() || !curves[static_cast<std::size_t>(id)]) return nullptr;
  return &curves[static_cast<std::size_t>(id)]->curve;
}

avar::playback::RawCurve decoded(const double* flat, int count) {
  return avar::playback::decode_raw_curve(std::span<const double>(flat, static_cast<std::size_t>(count)));
}

}  // namespace

extern "C" {

/// Builds a curve from `count` numbers at `flat`; its number, or -1 (see avar_error()).
int avar_curve_build(const double* flat, int count) {
  try {
    avar::playback::RawCurve raw = decoded(flat, count);
    auto built = std::make_unique<Built>(Built{avar::playback::Curve::build(raw), std::move(raw)});
    for (std::size_t i = 0; i < curves.size(); ++i)
      if (!curves[i]) {
        curves[i] = std::move(built);
        return static_cast<int>(i);
      }
    curves.push_back(std::move(built));
    return static_cast<int>(curves.size()) - 1;
  } catch (const std::exception& e) {
    last_error = e.what();
    return -1;
  }
}

/// Builds curve `id` again from new keys (an edit of them), reusing the segments the edit left
/// alone (Curve::build's rebuild: the same bits as a fresh build). 0, or -1 with the curve
/// unchanged (see avar_error()).
int avar_curve_rebuild(int id, const double* flat, int count) {
  if (!find(id)) {
    last_error = "no curve " + std::to_string(id);
    return -1;
  }
  try {
    Built& old = *curves[static_cast<std::size_t>(id)];
    avar::playback::RawCurve raw = decoded(flat, count);
    avar::playback::Curve curve = avar::playback::Curve::build(raw, old.curve, old.raw);
    old = Built{std::move(curve), std::move(raw)};
    return 0;
  } catch (const std::exception& e) {
    last_error = e.what();
    return -1;
  }
}

/// Frees a curve's number for reuse.
void avar_curve_free(int id) {
  if (find(id)) curves[static_cast<std::size_t>(id)].reset();
}

/// The curve's value at `t` seconds (0 for a curve that does not exist).
double avar_curve_sample(int id, double t) {
  const avar::playback::Curve* curve = find(id);
  return curve ? curve->evaluate(t) : 0.0;
}

/// Values at `count` times, written to `out`.
void avar_curve_sample_many(int id, const double* times, double* out, int count) {
  const avar::playback::Curve* curve = find(id);
  for (int i = 0; i < count; ++i) out[i] = curve ? curve->evaluate(times[i]) : 0.0;
}

/// The Bezier handles of every key of the flat keys, as the engine computes them when it builds
/// the curve (Blender's rules for auto, auto_clamped, vector and aligned sides): 4 numbers per key
/// written to `out` (left time, left value, right time, right value; NaN for a side without a
/// handle). Returns the key count, or -1 (see avar_error()).
int avar_curve_handles(const double* flat, int count, double* out) {
  try {
    const avar::playback::RawCurve raw = decoded(flat, count);
    const std::vector<avar::playback::ResolvedHandles> handles = avar::playback::compute_handles(raw);
    constexpr double none = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < handles.size(); ++k) {
      const auto& h = handles[k];
      out[4 * k + 0] = h.left ? h.left->time : none;
      out[4 * k + 1] = h.left ? h.left->value : none;
      out[4 * k + 2] = h.right ? h.right->time : none;
      out[4 * k + 3] = h.right ? h.right->value : none;
    }
    return static_cast<int>(handles.size());
  } catch (const std::exception& e) {
    last_error = e.what();
    return -1;
  }
}

/// Why the last build failed.
const char* avar_error() { return last_error.c_str(); }

}  // extern "C"
