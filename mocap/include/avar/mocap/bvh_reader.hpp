#pragma once
// Biovision Hierarchy (BVH) motion capture files into the skeleton-animation model.
// Load time only: allocates and throws; not for the tick.
//
// What is read: HIERARCHY with one ROOT, JOINTs and End Sites nested in braces, each with an
// OFFSET and (End Sites excepted) CHANNELS: any of Xposition Yposition Zposition Xrotation
// Yrotation Zrotation (names case-insensitive), each at most once, in any order; then MOTION with
// `Frames: N`, `Frame Time: T` (seconds) and N rows, one frame per line, holding every joint's
// channel values in hierarchy order. Whitespace is spaces or tabs, lines end in LF or CRLF,
// blank lines are ignored. Joint names are the rest of the ROOT/JOINT line (they may hold spaces).
//
// Conventions (the model's axes and units are the file's own, nothing is converted):
// - Rotation channels are in degrees and compose in the order they are listed, the first
//   outermost: "Zrotation Xrotation Yrotation" gives the local rotation Rz(z) * Rx(x) * Ry(y),
//   so a vector in the joint's frame is turned about Y first, then X, then Z.
// - Position channels ADD to the OFFSET: local translation = OFFSET + (Xposition, Yposition,
//   Zposition), a missing position channel counting 0. Files whose position-carrying joints have
//   a zero OFFSET (the CMU database and most exporters' roots) read the same under the other
//   common reading (channels replace OFFSET).
// - An End Site becomes a leaf joint named "<parent>_end" with end_site = true, its OFFSET as
//   translation and no channels.
// - Rotations are made to agree in hemisphere frame to frame (align_hemispheres).
// - SkeletonAnimation::channels lists each joint's channel names in file order (canonical
//   spelling, e.g. "Zrotation").
//
// The whole file is validated before anything is returned: every problem throws avar::InputError
// at "file:line:column" saying what was found and what was expected (truncated hierarchy,
// missing braces, unknown keywords or channels, several ROOTs, duplicate joint names, rows whose
// value count differs from the channels', fewer or more rows than Frames:, values that are not
// finite numbers, a Frame Time that is not a positive number).

#include <string>
#include <string_view>

#include "avar/mocap/skeleton_animation.hpp"

namespace avar::mocap {

/// Reads and validates the BVH file at `path` (errors name `path`). Throws avar::InputError.
SkeletonAnimation load_bvh(const std::string& path);

/// Parses BVH text; `source` names it in errors and becomes SkeletonAnimation::source. Throws
/// avar::InputError. The entry point for tests and fuzzing: any text either parses or throws
/// InputError.
SkeletonAnimation parse_bvh(std::string_view text, const std::string& source);

}  // namespace avar::mocap
