// A lip-sync cue file as a user names it in a show (`cues:`) or on the command line: Rhubarb TSV
// or JSON, or a Papagayo/Moho switch file, told apart by content. read_viseme_cues must return
// cues in time order with 0 <= start <= end, all finite, or throw an InputError, nothing else.
// The reader takes a path, so each input is written whole to a file. The first byte picks the
// frames per second of Moho files (its value + 1) and stays part of the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/config/viseme_cues.hpp"
#include "avar/core/input_error.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const double fps = size > 0 ? data[0] + 1.0 : 24.0;
  const auto path = avar::fuzz::write_input_file("cues.txt", data, size);
  try {
    const auto cues = avar::config::read_viseme_cues(path.string(), fps, avar::SourceLocation{"show.yaml", 1, 1});
    double previous_start = 0;
    for (const auto& cue : cues) {
      if (!std::isfinite(cue.start) || !std::isfinite(cue.end) || cue.start < previous_start || cue.end < cue.start) std::abort();
      previous_start = cue.start;
    }
  } catch (const avar::InputError&) {
  }
  return 0;
}
