// The CSV of recorded samples `avar fit` reads: the reader must return a recording or throw an
// InputError; a recording it returns (up to 64 rows: the fit's cost grows with them) must then fit
// every channel within the tolerance without any other exception.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "avar/core/input_error.hpp"
#include "avar/playback/offline/curve_fit.hpp"
#include "avar/config/recording_csv.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream text(avar::fuzz::as_text(data, size));
  try {
    const avar::config::Recording recording = avar::config::read_recording(text, "fuzz.csv");
    if (recording.times.size() > 64) return 0;
    avar::playback::CurveFitOptions options;
    options.tolerance = 0.01;
    for (const auto& values : recording.values) (void)avar::playback::fit_curve(recording.times, values, options);
  } catch (const avar::InputError&) {
  }
  return 0;
}
