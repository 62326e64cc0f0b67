// The playback layers' rule (playback/CMakeLists.txt): runtime includes only runtime and core;
// offline includes runtime, offline and core; the runtime sources never call the construction
// entry points that the offline layer defines.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kPlaybackDir = fs::path(AVAR_SOURCE_DIR) / "playback";

std::vector<fs::path> layer_files(const std::string& layer) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kPlaybackDir / layer))
    if (entry.is_regular_file() && (entry.path().extension() == ".hpp" || entry.path().extension() == ".cpp"))
      files.push_back(entry.path());
  return files;
}

// Every quoted include of an avar header ("avar/...") that does not start with one of `allowed`,
// as "file: line".
std::vector<std::string> layering_violations(const std::string& layer, const std::vector<std::string>& allowed) {
  std::vector<std::string> found;
  for (const fs::path& file : layer_files(layer)) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
      const auto quote = line.find("#include \"avar/");
      if (quote == std::string::npos) continue;
      const std::string target = line.substr(quote + 10);
      bool ok = false;
      for (const std::string& prefix : allowed) ok = ok || target.rfind(prefix, 0) == 0;
      if (!ok) found.push_back(file.string() + ": " + line);
    }
  }
  return found;
}

TEST(PlaybackLayering, BothLayersHaveFiles) {
  EXPECT_GT(layer_files("runtime").size(), 20u);
  EXPECT_GT(layer_files("offline").size(), 5u);
}

TEST(PlaybackLayering, RuntimeIncludesOnlyRuntimeAndCore) {
  for (const std::string& v : layering_violations("runtime", {"avar/playback/runtime/", "avar/core/"})) ADD_FAILURE() << v;
}

TEST(PlaybackLayering, OfflineIncludesOnlyPlaybackAndCore) {
  for (const std::string& v : layering_violations("offline", {"avar/playback/runtime/", "avar/playback/offline/", "avar/core/"}))
    ADD_FAILURE() << v;
}

// Curve::build, DistanceTime::from_keys and PathTrack's constructor are declared on the runtime
// types but defined offline: a runtime source that called them would need the offline library.
TEST(PlaybackLayering, RuntimeSourcesDoNotBuild) {
  for (const fs::path& file : layer_files("runtime/src")) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
      for (const char* call : {"Curve::build(", "from_keys(", "PathTrack("})
        if (line.find(call) != std::string::npos) ADD_FAILURE() << file.string() << ": " << line;
  }
}

}  // namespace
