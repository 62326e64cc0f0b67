#pragma once
// What every timecode decoder promises about a fix it reports: a label valid for its rate and a
// finite position.
#include <cmath>
#include <cstdlib>

#include "avar/inputs/timecode_fix.hpp"

namespace avar::fuzz {

inline void check_timecode_fix(const avar::inputs::TimecodeFix& fix) {
  if (!avar::valid(fix.label) || !std::isfinite(fix.frames_after) || !std::isfinite(fix.seconds())) std::abort();
}

}  // namespace avar::fuzz
