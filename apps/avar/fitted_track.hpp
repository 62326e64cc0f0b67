#pragma once
// The fitter of samples into a track lives in playback (avar/playback/offline/track_fit.hpp) so
// that show loading can use it too; the commands name it here.

#include "avar/playback/offline/track_fit.hpp"

namespace avar::app {

using playback::fit_track;
using playback::max_fit_error;

}  // namespace avar::app
