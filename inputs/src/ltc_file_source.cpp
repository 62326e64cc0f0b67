#include "avar/inputs/ltc_file_source.hpp"

#include <algorithm>
#include <ctime>
#include <cerrno>
#include <cmath>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"

namespace avar::inputs {
namespace {

constexpr std::size_t kLtcBlockSamples = 256;  // an audio device's period

}  // namespace

LtcFileSource::LtcFileSource(std::string path, bool stepped)
    : path_(std::move(path)), stepped_(stepped), audio_(read_mono_audio(path_)), feed_(audio_.sample_rate) {}

LtcFileSource::~LtcFileSource() { stop(); }

std::string LtcFileSource::describe() const {
  return "LTC from " + path_ + " (" + std::to_string(static_cast<int>(audio_.sample_rate)) + " Hz, " +
         (stepped_ ? "on the simulated clock" : "played in real time") + ")";
}

void LtcFileSource::decode_until(std::size_t end, std::int64_t start_ns) noexcept {
  end = std::min(end, audio_.samples.size());
  const auto fed = static_cast<std::size_t>(feed_.fed());
  if (end <= fed) return;
  const auto end_ns = static_cast<std::int64_t>(std::llround(static_cast<double>(end) * 1e9 / audio_.sample_rate));
  feed_.feed(std::span(audio_.samples.data() + fed, end - fed), start_ns + end_ns);
}

void LtcFileSource::advance_to(std::int64_t now_ns) noexcept {
  if (!stepped_ || now_ns < 0) return;
  decode_until(static_cast<std::size_t>(static_cast<double>(now_ns) * 1e-9 * audio_.sample_rate), 0);
}

void LtcFileSource::start() {
  if (stepped_ || thread_.joinable()) return;
  stopping_.store(false);
  thread_ = std::thread([this] { play(); });
}

void LtcFileSource::stop() noexcept {
  stopping_.store(true);
  if (thread_.joinable()) thread_.join();
}

void LtcFileSource::play() noexcept {
  const std::int64_t start_ns = monotonic_ns();
  for (std::size_t end = kLtcBlockSamples; static_cast<std::size_t>(feed_.fed()) < audio_.samples.size() && !stopping_.load();
       end += kLtcBlockSamples) {
    // The block is there once its last sample has played.
    const auto due = start_ns + static_cast<std::int64_t>(static_cast<double>(end) * 1e9 / audio_.sample_rate);
    const timespec deadline{static_cast<time_t>(due / 1'000'000'000), static_cast<long>(due % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
    }
    decode_until(end, start_ns);
  }
}

}  // namespace avar::inputs
