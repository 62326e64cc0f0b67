#pragma once
// Any supported motion-capture file into the skeleton-animation model, chosen by the file's
// extension (case-insensitive): .bvh (bvh_reader.hpp), .gltf and .glb (gltf_reader.hpp). Load time only: allocates and throws.

#include <cstdint>
#include <string>

#include "avar/mocap/skeleton_animation.hpp"

namespace avar::mocap {

enum class MocapFormat : std::uint8_t { bvh, gltf, glb };

struct MocapLoadOptions {
  /// Frames per second a format without frames of its own is sampled at (> 0). BVH files keep
  /// their own frames and ignore it.
  double sample_rate_hz = 30;
};

/// The format of `path` by its extension; throws avar::InputError naming the file and the
/// extensions that are supported otherwise.
MocapFormat mocap_format(const std::string& path);

/// "BVH", "glTF 2.0 (JSON)", "glTF 2.0 (binary .glb)".
const char* to_string(MocapFormat format);

/// Reads and validates `path` with the reader of its format. Throws avar::InputError.
SkeletonAnimation load_mocap_file(const std::string& path, const MocapLoadOptions& options = {});

}  // namespace avar::mocap
