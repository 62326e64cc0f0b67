#include "avar/session/timecode_run.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/inputs/alsa_ltc_source.hpp"
#include "avar/inputs/ltc_file_source.hpp"
#include "avar/inputs/timecode_inputs.hpp"

namespace avar::session {
namespace {

constexpr const char* kTimecodeForms =
    "expected ltc:FILE.wav, ltc:alsa:DEVICE, mtc:PORT, artnet, artnet:PORT or artnet:HOST:PORT";

std::uint16_t timecode_port(std::string_view text, const std::string& spec) {
  unsigned value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size() || value == 0 || value > 65535)
    throw std::invalid_argument("--timecode " + spec + ": '" + std::string(text) + "' is not a UDP port (1 to 65535)");
  return static_cast<std::uint16_t>(value);
}

}  // namespace

std::unique_ptr<inputs::TimecodeSource> open_timecode_source(const std::string& spec, bool fast) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "ltc") {
    if (rest.empty()) throw std::invalid_argument("--timecode ltc: needs a file, ltc:FILE.wav");
    if (rest.rfind("alsa:", 0) == 0) {
      const std::string device = rest.substr(5);
      if (device.empty())
        throw std::invalid_argument("--timecode " + spec + ": needs a capture device, ltc:alsa:DEVICE (default, hw:1,0 ...)");
      if (fast) throw std::invalid_argument("--timecode " + spec + ": a live timecode source needs the wall clock; drop --fast");
      return std::make_unique<inputs::AlsaLtcSource>(device);
    }
    return std::make_unique<inputs::LtcFileSource>(rest, fast);
  }
  if (fast) throw std::invalid_argument("--timecode " + spec + ": a live timecode source needs the wall clock; drop --fast");
  if (kind == "mtc") {
    if (rest.empty()) throw std::invalid_argument("--timecode mtc: needs a MIDI port, mtc:PORT (`avar inputs list` names them)");
    return std::make_unique<inputs::MtcInput>(rest);
  }
  if (kind == "artnet") {
    if (rest.empty()) return std::make_unique<inputs::ArtnetTimecodeInput>();
    const auto second = rest.find(':');
    if (second == std::string::npos) return std::make_unique<inputs::ArtnetTimecodeInput>("127.0.0.1", timecode_port(rest, spec));
    try {
      return std::make_unique<inputs::ArtnetTimecodeInput>(rest.substr(0, second), timecode_port(rest.substr(second + 1), spec));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--timecode " + spec + ": " + e.what());
    }
  }
  throw std::invalid_argument("--timecode '" + spec + "': " + kTimecodeForms);
}

TimecodeRun::TimecodeRun(const ShowControlOptions& options, bool fast, std::size_t expected_ticks) {
  control::ChaseOptions chase;
  chase.freewheel_s = options.freewheel_s;
  if (options.offset) {
    // Parsed at 30 labels a second (the most any rate has); read at the source's rate on lock.
    std::string why;
    const auto label = parse_timecode(*options.offset, FrameRate::fps30, &why);
    if (!label) throw std::invalid_argument("--offset: " + why);
    chase.offset_label = label;
  }
  source_ = open_timecode_source(options.source.value_or(""), fast);
  chase_ = std::make_unique<control::ChaseClock>(*source_, chase, source_->stepped() ? nullptr : control::monotonic_ns);
  show_time_.reserve(expected_ticks);
  clock_s_.reserve(expected_ticks);
  error_ms_.reserve(expected_ticks);
}

TimecodeRun::~TimecodeRun() { stop(); }

void TimecodeRun::start() { source_->start(); }

void TimecodeRun::stop() noexcept { source_->stop(); }

void TimecodeRun::after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // The chase read the clock this tick only while the show ran.
  const bool ran = controller.phase() == control::Phase::running;
  show_time_.push_back(ran ? controller.show_time() : kNone);
  clock_s_.push_back(ran ? chase_->last_clock_s() : kNone);
  error_ms_.push_back(ran ? chase_->last_error_s() * 1e3 : kNone);
  if (inner_) inner_->after_tick(tick, now_s, dt_s, lateness_s, controller);
}

void TimecodeRun::summarize(std::ostream& out) const {
  const inputs::TimecodeCounters k = source_->counters();
  out << "timecode: " << source_->describe() << "; " << k.fixes << " positions, " << k.partial << " partial, " << k.ignored
      << " ignored, " << k.bad << " bad (dropped)\n";
  const control::LatencyHistogram& e = chase_->errors();
  const auto ms = [](std::int64_t ns) { return format_fixed(static_cast<double>(ns) / 1e6, 3); };
  if (e.count() == 0) {
    out << "chase: no timecode arrived while the show ran\n";
  } else {
    out << "chase error |show - source| (ms): p50 " << ms(e.percentile_ns(0.5)) << ", p99 " << ms(e.percentile_ns(0.99))
        << ", max " << ms(e.max_ns()) << " over " << e.count() << " ticks; " << chase_->jumps() << " jumps; rate "
        << format_fixed(chase_->rate(), 5) << '\n';
  }
  if (source_lost())
    out << "chase: the timecode stopped; freewheeled " << format_number(chase_->options().freewheel_s)
        << " s, then eased to rest\n";
}

std::vector<TraceColumn> TimecodeRun::trace_columns() const {
  return {{"show_time", show_time_}, {"chase_clock_s", clock_s_}, {"chase_error_ms", error_ms_}};
}

}  // namespace avar::session
