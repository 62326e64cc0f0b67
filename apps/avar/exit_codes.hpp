#pragma once
// Exit codes of the avar command line.

namespace avar::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;     ///< bad command line, rig, show or port: nothing moved
inline constexpr int kExitFault = 3;        ///< a fault stopped the show (link failure, bad data)
inline constexpr int kExitInterrupted = 130;///< stopped by Ctrl-C / SIGTERM after easing to rest

}  // namespace avar::app
