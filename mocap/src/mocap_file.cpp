#include "avar/mocap/mocap_file.hpp"

#include <algorithm>
#include <filesystem>

#include "avar/core/input_error.hpp"
#include "avar/mocap/bvh_reader.hpp"

namespace avar::mocap {

MocapFormat mocap_format(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; });
  if (extension == ".bvh") return MocapFormat::bvh;
  throw InputError({path, 0, 0}, "unknown motion-capture format '" + extension + "'; expected a .bvh file");
}

const char* to_string(MocapFormat format) {
  switch (format) {
    case MocapFormat::bvh: return "BVH";
  }
  return "?";
}

SkeletonAnimation load_mocap_file(const std::string& path, const MocapLoadOptions& /*options*/) {
  switch (mocap_format(path)) {
    case MocapFormat::bvh: return load_bvh(path);
  }
  return load_bvh(path);
}

}  // namespace avar::mocap
