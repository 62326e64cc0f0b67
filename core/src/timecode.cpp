#include "avar/core/timecode.hpp"

#include <array>
#include <charconv>
#include <cstdio>

namespace avar {
namespace {

constexpr std::int64_t kDropFramesPerTenMinutes = 17982;  // 10 * 60 * 30 - 9 * 2
constexpr std::int64_t kDropFramesPerMinute = 1798;       // 60 * 30 - 2 (minutes not divisible by 10)

}  // namespace

int nominal_fps(FrameRate r) noexcept {
  switch (r) {
    case FrameRate::fps24: return 24;
    case FrameRate::fps25: return 25;
    case FrameRate::fps29_97df:
    case FrameRate::fps30: return 30;
  }
  return 30;
}

double frames_per_second(FrameRate r) noexcept {
  return r == FrameRate::fps29_97df ? 30000.0 / 1001.0 : static_cast<double>(nominal_fps(r));
}

const char* to_string(FrameRate r) noexcept {
  switch (r) {
    case FrameRate::fps24: return "24";
    case FrameRate::fps25: return "25";
    case FrameRate::fps29_97df: return "29.97df";
    case FrameRate::fps30: return "30";
  }
  return "?";
}

std::int64_t frames_per_day(FrameRate r) noexcept {
  if (r == FrameRate::fps29_97df) return 24 * 6 * kDropFramesPerTenMinutes;
  return std::int64_t{24} * 3600 * nominal_fps(r);
}

bool valid(const Timecode& t) noexcept {
  if (t.hours < 0 || t.hours > 23 || t.minutes < 0 || t.minutes > 59 || t.seconds < 0 || t.seconds > 59) return false;
  if (t.frames < 0 || t.frames >= nominal_fps(t.rate)) return false;
  const bool dropped = t.rate == FrameRate::fps29_97df && t.seconds == 0 && t.frames < 2 && t.minutes % 10 != 0;
  return !dropped;
}

std::int64_t to_frame_number(const Timecode& t) noexcept {
  const std::int64_t fps = nominal_fps(t.rate);
  const std::int64_t total_minutes = std::int64_t{60} * t.hours + t.minutes;
  std::int64_t labels = ((total_minutes * 60) + t.seconds) * fps + t.frames;
  // Two labels skipped in every minute not divisible by ten.
  if (t.rate == FrameRate::fps29_97df) labels -= 2 * (total_minutes - total_minutes / 10);
  return labels;
}

Timecode from_frame_number(std::int64_t frame, FrameRate rate) noexcept {
  const std::int64_t day = frames_per_day(rate);
  frame %= day;
  if (frame < 0) frame += day;
  std::int64_t labels = frame;
  if (rate == FrameRate::fps29_97df) {
    // Put back the skipped labels: 18 per whole ten minutes, 2 per whole minute after the
    // first (undropped) minute of the ten.
    const std::int64_t tens = frame / kDropFramesPerTenMinutes;
    const std::int64_t rest = frame % kDropFramesPerTenMinutes;
    labels += 18 * tens;
    if (rest >= 2) labels += 2 * ((rest - 2) / kDropFramesPerMinute);
  }
  const std::int64_t fps = nominal_fps(rate);
  Timecode t;
  t.rate = rate;
  t.frames = static_cast<int>(labels % fps);
  const std::int64_t secs = labels / fps;
  t.seconds = static_cast<int>(secs % 60);
  t.minutes = static_cast<int>((secs / 60) % 60);
  t.hours = static_cast<int>(secs / 3600);
  return t;
}

double to_seconds(const Timecode& t) noexcept { return static_cast<double>(to_frame_number(t)) / frames_per_second(t.rate); }

std::string to_string(const Timecode& t) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%02d:%02d:%02d%c%02d", t.hours, t.minutes, t.seconds,
                t.rate == FrameRate::fps29_97df ? ';' : ':', t.frames);
  return text.data();
}

std::optional<Timecode> parse_timecode(std::string_view text, FrameRate rate, std::string* why) {
  const auto fail = [&](std::string reason) -> std::optional<Timecode> {
    if (why) *why = std::move(reason);
    return std::nullopt;
  };
  std::array<int, 4> fields{};
  std::size_t at = 0;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) {
      const char sep = at < text.size() ? text[at] : '\0';
      const bool ok = sep == ':' || (i == 3 && (sep == ';' || sep == '.'));
      if (!ok) return fail("'" + std::string(text) + "' is not a timecode: expected HH:MM:SS:FF (or HH:MM:SS;FF for drop-frame)");
      ++at;
    }
    const char* begin = text.data() + at;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(begin, end, fields[i]);
    if (error != std::errc{} || stop - begin != 2)
      return fail("'" + std::string(text) + "' is not a timecode: expected two digits per field, HH:MM:SS:FF");
    at += 2;
  }
  if (at != text.size()) return fail("'" + std::string(text) + "' has more after HH:MM:SS:FF");
  const Timecode t{fields[0], fields[1], fields[2], fields[3], rate};
  if (!valid(t))
    return fail(
        "'" + std::string(text) + "' is out of range at " + to_string(rate) +
        " fps (hours 0-23, minutes and seconds 0-59, frames 0-" + std::to_string(nominal_fps(rate) - 1) +
        (rate == FrameRate::fps29_97df ? "; frames 00 and 01 do not exist at the start of a minute not divisible by 10" : "") +
        ")");
  return t;
}

std::optional<FrameRate> parse_frame_rate(std::string_view text) noexcept {
  if (text == "24") return FrameRate::fps24;
  if (text == "25") return FrameRate::fps25;
  if (text == "29.97" || text == "29.97df") return FrameRate::fps29_97df;
  if (text == "30") return FrameRate::fps30;
  return std::nullopt;
}

}  // namespace avar
