#pragma once
// Where show time comes from while a show runs. Without one, show time is the loop time since
// the show started; a ShowClock (the timecode chase) maps each running tick to a show time of its
// own, and may ask for the run to end (the source is gone): the controller then eases to rest as
// on a stop request. Whatever show time it gives, the commands still go through the limiter:
// a jump of show time moves the figure on a limited profile, never a snap.

namespace avar::control {

struct ShowClockReading {
  double show_time_s = 0;  ///< seconds into the show (>= 0)
  bool stop = false;       ///< end the run: ease to rest
};

class ShowClock {
 public:
  virtual ~ShowClock() = default;
  /// Called once per running tick with the loop time. Loop thread; must be real-time safe.
  virtual ShowClockReading read(double now_s) noexcept = 0;
};

}  // namespace avar::control
