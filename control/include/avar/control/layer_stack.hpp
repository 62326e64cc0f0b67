#pragma once
// Several live layers as the controller's one LiveLayer, applied bottom (first) to top: each
// sees what the ones below made of the show's frame, so a later layer outranks an earlier one
// where both drive a channel. The arbitration order of a run is then
//   fault / e-stop (the supervisor: no layer is applied once it has faulted)
//   > puppeteer (LiveInputs, on top) > show > idle (IdleLayer, at the bottom, yields to the show).

#include <span>
#include <vector>

#include "avar/control/live_layer.hpp"

namespace avar::control {

class LayerStack final : public LiveLayer {
 public:
  /// The layers are borrowed (they must outlive the stack); null entries are skipped.
  /// Construction allocates; apply() is real-time safe when every layer's is.
  explicit LayerStack(std::vector<LiveLayer*> bottom_to_top) : layers_(std::move(bottom_to_top)) {}

  void apply(double now_s, std::span<double> frame) noexcept override {
    for (LiveLayer* layer : layers_)
      if (layer) layer->apply(now_s, frame);
  }
  void apply_targets(double now_s, std::span<double> points) noexcept override {
    for (LiveLayer* layer : layers_)
      if (layer) layer->apply_targets(now_s, points);
  }

 private:
  std::vector<LiveLayer*> layers_;
};

}  // namespace avar::control
