// avar_fuzz_replay TARGET [FILE|DIR]...: runs the empty input and then every file given (every
// regular file of a directory, recursively, in name order) through one fuzz target's
// LLVMFuzzerTestOneInput, the way libFuzzer would replay a corpus. Without paths it replays the
// target's seed corpus, fuzz/corpus/TARGET. A crash is the sanitizers' to report (the ordinary
// sanitizer tree); a clean run prints how many inputs it ran and exits 0. `--list` prints the
// targets. Exit 2: a bad command line or an unreadable path.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "replay_registry.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> replay_inputs(const fs::path& path) {
  std::vector<fs::path> files;
  if (fs::is_directory(path)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(path))
      if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
  } else if (fs::is_regular_file(path)) {
    files.push_back(path);
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  const std::span<const avar::fuzz::ReplayTarget> targets = avar::fuzz::replay_targets();
  if (argc >= 2 && std::string_view(argv[1]) == "--list") {
    for (const avar::fuzz::ReplayTarget& t : targets) std::printf("%s\n", t.name);
    return 0;
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TARGET [FILE|DIR]...  (or --list)\n", argv[0]);
    return 2;
  }
  const auto target =
      std::find_if(targets.begin(), targets.end(), [&](const auto& t) { return argv[1] == std::string_view(t.name); });
  if (target == targets.end()) {
    std::fprintf(stderr, "unknown fuzz target '%s'; --list prints the targets\n", argv[1]);
    return 2;
  }
  std::vector<fs::path> paths(argv + 2, argv + argc);
  if (paths.empty()) paths.push_back(fs::path(AVAR_FUZZ_CORPUS_DIR) / target->name);

  static const std::uint8_t kEmpty = 0;
  target->run(&kEmpty, 0);
  std::size_t count = 1;
  for (const fs::path& path : paths) {
    const std::vector<fs::path> files = replay_inputs(path);
    if (files.empty() && !fs::is_directory(path)) {
      std::fprintf(stderr, "cannot read '%s'; expected a file or a directory of inputs\n", path.c_str());
      return 2;
    }
    for (const fs::path& file : files) {
      std::ifstream in(file, std::ios::binary);
      const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      if (!in.good() && !in.eof()) {
        std::fprintf(stderr, "cannot read '%s'\n", file.c_str());
        return 2;
      }
      target->run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++count;
    }
  }
  std::printf("%s: replayed %zu inputs\n", target->name, count);
  return 0;
}
