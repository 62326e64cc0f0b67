#include "avar/mocap/mocap_file.hpp"

#include <algorithm>
#include <filesystem>

#include "avar/core/input_error.hpp"
#include "avar/mocap/bvh_reader.hpp"
#include "avar/mocap/gltf_reader.hpp"

namespace avar::mocap {

MocapFormat mocap_format(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; });
  if (extension == ".bvh") return MocapFormat::bvh;
  if (extension == ".gltf") return MocapFormat::gltf;
  if (extension == ".glb") return MocapFormat::glb;
  throw InputError({path, 0, 0}, "unknown motion-capture format '" + extension + "'; expected .bvh, .gltf or .glb");
}

const char* to_string(MocapFormat format) {
  switch (format) {
    case MocapFormat::bvh: return "BVH";
    case MocapFormat::gltf: return "glTF 2.0 (JSON)";
    case MocapFormat::glb: return "glTF 2.0 (binary .glb)";
  }
  return "?";
}

SkeletonAnimation load_mocap_file(const std::string& path, const MocapLoadOptions& options) {
  if (mocap_format(path) == MocapFormat::bvh) return load_bvh(path);
  GltfReadOptions gltf;
  gltf.sample_rate_hz = options.sample_rate_hz;
  return load_gltf(path, gltf);
}

}  // namespace avar::mocap
