#include "avar/inputs/alsa_ltc_source.hpp"

#include <alsa/asoundlib.h>

#include <cerrno>
#include <chrono>
#include <stdexcept>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"

namespace avar::inputs {
namespace {

constexpr unsigned kAlsaLtcRate = 48000;
constexpr snd_pcm_uframes_t kAlsaLtcPeriodFrames = 256;
constexpr int kAlsaLtcWaitMs = 100;  // how long stop() may wait for the capture thread

}  // namespace

struct AlsaLtcSource::Pcm {
  snd_pcm_t* handle = nullptr;
  ~Pcm() {
    if (handle) snd_pcm_close(handle);
  }
};

AlsaLtcSource::AlsaLtcSource(std::string device) : device_(std::move(device)) {}

AlsaLtcSource::~AlsaLtcSource() { stop(); }

void AlsaLtcSource::start() {
  if (thread_.joinable()) return;
  const auto fail = [this](const char* what, int code) {
    return std::runtime_error("ALSA capture device '" + device_ + "': cannot " + what + " (" + snd_strerror(code) + ")");
  };
  auto pcm = std::make_unique<Pcm>();
  if (const int e = snd_pcm_open(&pcm->handle, device_.c_str(), SND_PCM_STREAM_CAPTURE, SND_PCM_NONBLOCK); e < 0) {
    pcm->handle = nullptr;
    throw fail("open", e);
  }
  snd_pcm_t* h = pcm->handle;
  snd_pcm_hw_params_t* hw = nullptr;
  snd_pcm_hw_params_alloca(&hw);
  if (const int e = snd_pcm_hw_params_any(h, hw); e < 0) throw fail("read its capabilities", e);
  if (const int e = snd_pcm_hw_params_set_access(h, hw, SND_PCM_ACCESS_RW_INTERLEAVED); e < 0)
    throw fail("capture interleaved", e);
  PcmSampleFormat format = PcmSampleFormat::f32;
  if (snd_pcm_hw_params_set_format(h, hw, SND_PCM_FORMAT_FLOAT) < 0) {
    format = PcmSampleFormat::s16;
    if (const int e = snd_pcm_hw_params_set_format(h, hw, SND_PCM_FORMAT_S16); e < 0)
      throw fail("capture float or signed 16-bit samples", e);
  }
  unsigned channels = 1;
  if (const int e = snd_pcm_hw_params_set_channels_near(h, hw, &channels); e < 0) throw fail("set the channels", e);
  unsigned rate = kAlsaLtcRate;
  if (const int e = snd_pcm_hw_params_set_rate_near(h, hw, &rate, nullptr); e < 0) throw fail("set the rate", e);
  snd_pcm_uframes_t period = kAlsaLtcPeriodFrames;
  if (const int e = snd_pcm_hw_params_set_period_size_near(h, hw, &period, nullptr); e < 0) throw fail("set the period", e);
  snd_pcm_uframes_t buffer = period * 8;
  if (const int e = snd_pcm_hw_params_set_buffer_size_near(h, hw, &buffer); e < 0) throw fail("set the buffer", e);
  if (const int e = snd_pcm_hw_params(h, hw); e < 0) throw fail("apply the capture settings", e);
  if (const int e = snd_pcm_hw_params_get_period_size(hw, &period, nullptr); e < 0) throw fail("read the period", e);
  try {
    feed_ = std::make_unique<LtcCaptureFeed>(static_cast<double>(rate), channels, format, period);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("ALSA capture device '" + device_ + "': " + e.what());
  }
  if (const int e = snd_pcm_prepare(h); e < 0) throw fail("prepare", e);
  if (const int e = snd_pcm_start(h); e < 0) throw fail("start capturing", e);
  pcm_ = std::move(pcm);
  stopping_.store(false);
  failure_.store(0);
  thread_ = std::thread([this] { capture(); });
}

void AlsaLtcSource::stop() noexcept {
  stopping_.store(true);
  if (thread_.joinable()) thread_.join();
  pcm_.reset();
}

TimecodeReading AlsaLtcSource::latest() const noexcept { return feed_ ? feed_->feed().latest() : TimecodeReading{}; }

TimecodeCounters AlsaLtcSource::counters() const noexcept { return feed_ ? feed_->feed().counters() : TimecodeCounters{}; }

std::string AlsaLtcSource::describe() const {
  std::string text = "LTC from ALSA capture device " + device_;
  if (feed_)
    text += " (" + std::to_string(static_cast<int>(feed_->feed().sample_rate())) + " Hz, " + std::to_string(feed_->channels()) +
            (feed_->channels() == 1 ? " channel" : " channels mixed") + ", " + std::to_string(overruns()) + " overruns)";
  if (const int e = failure_.load(); e != 0) text += "; capture failed: " + std::string(snd_strerror(e));
  return text;
}

void AlsaLtcSource::capture() noexcept {
  snd_pcm_t* h = pcm_->handle;
  const double ns_per_frame = 1e9 / feed_->feed().sample_rate();
  while (!stopping_.load()) {
    int e = snd_pcm_wait(h, kAlsaLtcWaitMs);
    snd_pcm_sframes_t got = 0;
    if (e > 0) {
      got = snd_pcm_readi(h, feed_->buffer(), feed_->period_frames());
      if (got > 0) {
        // The period's end arrived as the frames still waiting behind it began to.
        const snd_pcm_sframes_t behind = snd_pcm_avail(h);
        const auto late = behind > 0 ? static_cast<std::int64_t>(static_cast<double>(behind) * ns_per_frame) : 0;
        feed_->take(static_cast<std::size_t>(got), monotonic_ns() - late);
        frames_captured_.fetch_add(static_cast<std::uint64_t>(got), std::memory_order_relaxed);
        continue;
      }
      e = static_cast<int>(got);
    }
    if (e == 0 || e == -EAGAIN) continue;  // nothing yet: look at stopping_ again
    if (e == -EPIPE) {
      overruns_.fetch_add(1, std::memory_order_relaxed);
      e = snd_pcm_prepare(h);
      if (e >= 0) e = snd_pcm_start(h);
    } else if (e == -ESTRPIPE) {
      // Resumed in place, or (a device that cannot resume) prepared and started afresh.
      while ((e = snd_pcm_resume(h)) == -EAGAIN && !stopping_.load()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (e < 0) {
        e = snd_pcm_prepare(h);
        if (e >= 0) e = snd_pcm_start(h);
      }
    }
    if (e < 0) {
      failure_.store(e);
      return;
    }
  }
}

}  // namespace avar::inputs
