#pragma once
// The sources avar export writes (the engine's, the figure's, the Arduino glue) and those its
// --verify builds beside a project, as this avar was built with them (embedded at build time by
// device/export/embed_sources.cmake). Paths: "src/..." go into a project, "verify/..." are the
// verification run's own.

#include <span>

namespace avar::device {

struct EmbeddedSource {
  const char* path;
  const char* text;
};

std::span<const EmbeddedSource> embedded_sources();

}  // namespace avar::device
