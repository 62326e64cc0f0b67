#pragma once
// An input source whose controls all carry a name of the user's: "pad" makes "ch1.cc7" arrive as
// "pad.ch1.cc7" and "jaw" as "pad.jaw", so two controllers of the same kind can be told apart.
// Direct channel controls ("channel/jaw", from OSC's /avar/channel/jaw) pass unchanged: they name
// a channel of the rig, whichever device sends them.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "avar/inputs/input_source.hpp"
#include "avar/inputs/osc_dispatch.hpp"

namespace avar::inputs {

class PrefixedInputSource final : public InputSource, private ControlSink {
 public:
  /// Longest control name delivered ("NAME." included); longer ones are counted as ignored.
  static constexpr std::size_t kMaxName = 256;

  /// `prefix`: non-empty (the factory checks its characters). Takes `inner`.
  PrefixedInputSource(std::string prefix, std::unique_ptr<InputSource> inner);
  ~PrefixedInputSource() override;

  void start(ControlSink& sink) override;
  void stop() noexcept override;
  /// "pad: OSC on udp 127.0.0.1:9000".
  std::string describe() const override;
  /// The inner source's, plus the controls dropped for too long a name as ignored.
  InputCounters counters() const noexcept override;

  const std::string& prefix() const noexcept { return prefix_; }
  InputSource& inner() noexcept { return *inner_; }

 private:
  void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept override;

  std::string prefix_;
  std::unique_ptr<InputSource> inner_;
  ControlSink* sink_ = nullptr;
  std::atomic<std::uint64_t> too_long_{0};
};

}  // namespace avar::inputs
