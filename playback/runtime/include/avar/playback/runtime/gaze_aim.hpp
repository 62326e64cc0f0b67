#pragma once
// Where look-at gaze looks (GazeLookAt), and the hook that turns it into eye channel values: the
// gaze generator decides the point, the aim (control::GazeLookAt, with the rig's kinematics)
// solves the eyes for it. Real-time safe.

#include <span>

namespace avar::playback {

/// A gaze target: a direction in the gaze frame (degrees: pan to the left, tilt up) and a
/// distance (m) from the eyes' centre.
struct GazePoint {
  double pan_deg = 0;
  double tilt_deg = 0;
  double distance_m = 1;
};

class GazeAim {
 public:
  virtual ~GazeAim() = default;
  /// Writes the eye channels that look at `point`, the figure posed as `frame` says (the head
  /// where the gaze generator has just put it). Real-time safe; called once per sample.
  virtual void aim(const GazePoint& point, std::span<double> frame) noexcept = 0;
};

}  // namespace avar::playback
