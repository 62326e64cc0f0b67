#pragma once
// SMPTE timecode (SMPTE ST 12-1): hours, minutes, seconds and frames at 24, 25, 29.97 drop-frame
// or 30 frames per second, and its mapping to a frame count and to seconds.
//
// Drop-frame (29.97): the labels 00 and 01 are skipped at the start of every minute except
// minutes 0, 10, 20, 30, 40 and 50, so that the labels keep up with a clock running at
// 30000/1001 frames per second (00:00:59;29 is followed by 00:01:00;02, 00:09:59;29 by
// 00:10:00;00). A frame count always counts real frames from 00:00:00:00.
//
// Pure: no allocation (except parse's error text), no clock; every function is real-time safe
// except parse_timecode.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace avar {

enum class FrameRate : std::uint8_t { fps24, fps25, fps29_97df, fps30 };

/// Labels per second: 24, 25, 30 (drop-frame counts 30 labels) or 30.
int nominal_fps(FrameRate r) noexcept;
/// Real frames per second: 24, 25, 30000/1001, 30.
double frames_per_second(FrameRate r) noexcept;
/// "24", "25", "29.97df", "30".
const char* to_string(FrameRate r) noexcept;
/// Frames in 24 hours at this rate (the count wraps there).
std::int64_t frames_per_day(FrameRate r) noexcept;

struct Timecode {
  int hours = 0;
  int minutes = 0;
  int seconds = 0;
  int frames = 0;
  FrameRate rate = FrameRate::fps25;

  friend bool operator==(const Timecode&, const Timecode&) = default;
};

/// True when every field is in range for the rate (a dropped drop-frame label is invalid).
bool valid(const Timecode& t) noexcept;

/// Frames since 00:00:00:00 (real frames; drop-frame labels skipped). Precondition: valid(t).
std::int64_t to_frame_number(const Timecode& t) noexcept;

/// The label of a frame count, wrapped into one day (negative counts wrap from the end).
Timecode from_frame_number(std::int64_t frame, FrameRate rate) noexcept;

/// Seconds since 00:00:00:00 at the rate's real frame rate (frame / frames_per_second).
double to_seconds(const Timecode& t) noexcept;

/// "HH:MM:SS:FF", with ';' before the frames for drop-frame.
std::string to_string(const Timecode& t);

/// Parses "HH:MM:SS:FF" (or "HH:MM:SS;FF" / "HH:MM:SS.FF", which mean drop-frame when the rate
/// is 29.97df) at `rate`. nullopt and `why` (what was expected) when malformed or out of range.
std::optional<Timecode> parse_timecode(std::string_view text, FrameRate rate, std::string* why = nullptr);

/// "24", "25", "29.97", "29.97df", "30" -> the rate; nullopt otherwise.
std::optional<FrameRate> parse_frame_rate(std::string_view text) noexcept;

}  // namespace avar
