#include "embedded_sources.hpp"

namespace avar::device {
namespace {

#include "avar_device_sources.inc"

}  // namespace

std::span<const EmbeddedSource> embedded_sources() { return kEmbeddedSources; }

}  // namespace avar::device
