#pragma once
// For readers that take only a path: the fuzzer's input written whole to a file `name` in a folder
// of this process's own (under the temporary directory; removed at exit), so that relative names inside the input
// (a buffer URI, a sound file) find nothing beside it. The file is replaced on every input.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace avar::fuzz {

/// The folder, made on first use and removed with everything in it when the process exits.
class InputFolder {
 public:
  InputFolder() : path_(std::filesystem::temp_directory_path() / ("avar_fuzz_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~InputFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  InputFolder(const InputFolder&) = delete;
  InputFolder& operator=(const InputFolder&) = delete;
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::filesystem::path write_input_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  static const InputFolder folder;
  const std::filesystem::path path = folder.path() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) std::abort();
  return path;
}

}  // namespace avar::fuzz
