// avar-bench-tick: the cost of one control tick for the 8-channel hello-head rig (sample the show,
// limit, calibrate, encode one Maestro packet, hand it to the transport), measured tick by tick.
// The transport discards the bytes, so the figure is avar's own work, not the link's.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "support/discard_transport.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/assembly/maestro_protocol.hpp"
#include "avar/firmware_iface/maestro_link.hpp"

namespace {

struct Head {
  avar::rig::Rig rig = avar::config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  avar::playback::Show show = avar::config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  avar::testing::DiscardTransport transport;
  avar::firmware_iface::MaestroLink link{transport, avar::assembly::maestro_config(rig, 0)};
};

void BM_TickHelloHead(benchmark::State& state) {
  Head head;
  head.show.loop = true;  // keep playing for as many ticks as the benchmark wants
  avar::control::Controller controller(head.rig, head.show, {&head.link}, {.tick_period_s = 0.001});
  controller.begin(0.0, head.rig.rest_frame());
  const double dt = 1.0 / 1000.0;
  std::vector<double> ns;
  ns.reserve(1 << 22);
  std::uint64_t k = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    controller.tick(static_cast<double>(k) * dt);
    benchmark::DoNotOptimize(controller.commanded().data());
    const auto t1 = std::chrono::steady_clock::now();
    if (ns.size() < ns.capacity()) ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    ++k;
  }
  std::sort(ns.begin(), ns.end());
  const auto at = [&](double fraction) { return ns.empty() ? 0.0 : ns[static_cast<std::size_t>(fraction * static_cast<double>(ns.size() - 1))]; };
  state.counters["median_ns"] = at(0.5);
  state.counters["worst_ns"] = at(1.0);
  state.counters["bytes_per_tick"] = static_cast<double>(head.link.last_send_size());
  // The worst case on a time-shared machine is usually the scheduler, not the tick; the upper
  // percentiles show how rare it is.
  std::printf("tick,rig=hello-head,channels=%zu,ticks=%zu,median_us=%.3f,p99_us=%.3f,p999_us=%.3f,worst_us=%.3f\n",
              head.rig.channels.size(), ns.size(), at(0.5) / 1000.0, at(0.99) / 1000.0, at(0.999) / 1000.0, at(1.0) / 1000.0);
}
BENCHMARK(BM_TickHelloHead)->Iterations(200000);

}  // namespace

BENCHMARK_MAIN();
