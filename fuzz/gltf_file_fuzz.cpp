// A glTF 2.0 file (JSON .gltf or binary .glb) as a user brings it: load_gltf must return a
// well-formed animation (finite values, unit rotations, one pose entry per joint, parents before
// children) or throw an InputError, nothing else. The reader takes a path, so each input is
// written whole to a file in a folder of this process's own; the first byte's low bit picks the
// name's extension (.glb or .gltf: the reader goes by the "glTF" magic, the name must not matter).
// Buffer URIs naming other files find nothing there (data: URIs are read).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "avar/core/input_error.hpp"
#include "avar/mocap/gltf_reader.hpp"
#include "skeleton_animation_check.hpp"

namespace {

std::filesystem::path gltf_fuzz_folder() {
  static const std::filesystem::path folder = [] {
    auto path = std::filesystem::temp_directory_path() / ("avar_fuzz_gltf_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary_name = size > 0 && (data[0] & 1U) != 0;
  const std::filesystem::path path = gltf_fuzz_folder() / (binary_name ? "input.glb" : "input.gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) std::abort();
  }
  try {
    avar::fuzz::check_skeleton_animation(avar::mocap::load_gltf(path.string()));
  } catch (const avar::InputError&) {
  }
  std::filesystem::remove(path);
  return 0;
}
