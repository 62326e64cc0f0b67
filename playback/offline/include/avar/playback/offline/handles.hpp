#pragma once
// Blender's F-curve handle computation (blenkernel BKE_fcurve_handles_recalc with
// BKE_nurb_handle_calc and BKE_nurb_handle_smooth_fcurve), so that keys given only with handle
// types (auto, auto_clamped, vector, aligned) get the handles Blender would give them. Load-time
// only: allocates.

#include <optional>
#include <vector>

#include "avar/playback/runtime/keys.hpp"

namespace avar::playback {

/// Both handles of a key after computation; a free side without a given handle stays empty.
struct ResolvedHandles {
  std::optional<Handle> left, right;
  HandleType left_type = HandleType::free, right_type = HandleType::free;
};

/// The side's type as the key gives it, or its default: free when the handle is given,
/// auto_clamped when not.
HandleType left_type_of(const RawKey& key) noexcept;
HandleType right_type_of(const RawKey& key) noexcept;

/// Whether Blender treats the curve as cyclic for its handles: a Cycles modifier repeating
/// (with or without offset) forever on both sides.
bool cyclic_for_handles(const Cycles& cycles) noexcept;

/// Handles of every key of `raw` (keys strictly increasing in time, finite), computed as
/// Blender does with every key selected: vector sides point a third of the way to the
/// neighbouring key, auto and auto_clamped sides follow the neighbours (auto_clamped keeps
/// extremes flat and does not overshoot), aligned sides turn to continue the other side,
/// first and last fully-auto keys lie flat under constant extrapolation, and with
/// continuous_acceleration the auto handles are solved for continuous curvature.
std::vector<ResolvedHandles> compute_handles(const RawCurve& raw);

}  // namespace avar::playback
