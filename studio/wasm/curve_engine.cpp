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

std::vector<std::unique_ptr<avar::playback::Curve>> curves;
std::string last_error;

const avar::playback::Curve* find(int id) {
  if (id < 0 || static_cast<std::size_t>(id) >= curves.size()) return nullptr;
  return curves[static_cast<std::size_t>(id)].get();
}

}  // namespace

extern "C" {

/// Builds a curve from `count` numbers at `flat`; its number, or -1 (see avar_error()).
int avar_curve_build(const double* flat, int count) {
  try {
    auto curve = std::make_unique<avar::playback::Curve>(avar::playback::Curve::build(
        avar::playback::decode_raw_curve(std::span<const double>(flat, static_cast<std::size_t>(count)))));
    for (std::size_t i = 0; i < curves.size(); ++i)
      if (!curves[i]) {
        curves[i] = std::move(curve);
        return static_cast<int>(i);
      }
    curves.push_back(std::move(curve));
    return static_cast<int>(curves.size()) - 1;
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
    const avar::playback::RawCurve raw =
        avar::playback::decode_raw_curve(std::span<const double>(flat, static_cast<std::size_t>(count)));
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
