// avar-bench-edit: the edit model under the studio's load. A seeded show of 64 channels and
// 100,000 Bezier keys over ten minutes; dragging a selection of 1,008 keys (63 on each of 16
// channels) is one MoveKeys group per pointer move: its apply (each touched curve checked and
// rebuilt) must fit in a frame, and so must its undo. Then 10,000 seeded random edits (add, move,
// replace, delete, ripple insert and delete) on the hello-head show, undone and redone whole: the
// saved file must be byte-identical to the original at one end and to the edited show at the
// other (counters identical_original and identical_edited, 1 when they are).
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "avar/edit/show_document.hpp"
#include "avar/rig/rig.hpp"
#include "avar/studio/studio.hpp"
#include "support/random_show_edits.hpp"

namespace {

namespace edit = avar::edit;
namespace playback = avar::playback;
using edit::KeyEdit;
using edit::ShowDocument;

constexpr int kChannels = 64;
constexpr int kKeysPerChannel = 100000 / kChannels;  // 1562
constexpr int kDraggedChannels = 16;
constexpr int kDraggedPerChannel = 63;

/// 64 tracks of Bezier keys with auto-clamped handles, 0.2 to 0.57 s apart (seeded).
ShowDocument big_show() {
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> u(0, 1);
  playback::Show show;
  show.name = "big";
  show.duration = 600;
  for (int c = 0; c < kChannels; ++c) {
    playback::RawCurve raw;
    double t = 0;
    for (int k = 0; k < kKeysPerChannel; ++k) {
      playback::RawKey key;
      key.time = t;
      key.value = -90 + 180 * u(rng);
      key.interpolation = playback::Interpolation::bezier;
      raw.keys.push_back(key);
      t += 0.2 + 0.17 * u(rng) + 0.2 * u(rng);
    }
    playback::Curve curve = playback::Curve::build(raw);
    show.tracks.push_back({"ch" + std::to_string(c), raw, std::move(curve), {}});
  }
  return ShowDocument(std::move(show));
}

/// One pointer move of the drag: 63 consecutive keys of each of 16 channels, 1 ms and 0.1 units.
std::vector<KeyEdit> drag_step(double sign) {
  std::vector<KeyEdit> group;
  for (int c = 0; c < kDraggedChannels; ++c) {
    std::vector<std::size_t> keys(kDraggedPerChannel);
    std::iota(keys.begin(), keys.end(), std::size_t{500});
    group.push_back(edit::MoveKeys{"ch" + std::to_string(c * 4), keys, sign * 0.001, sign * 0.1});
  }
  return group;
}

void BM_DragThousandKeys(benchmark::State& state) {
  ShowDocument doc = big_show();
  const std::vector<KeyEdit> there = drag_step(1), back = drag_step(-1);
  bool forth = true;
  for (auto _ : state) {
    doc.apply(forth ? there : back);  // the drag goes back and forth: the keys stay in order
    forth = !forth;
  }
  state.counters["keys_moved"] = kDraggedChannels * kDraggedPerChannel;
  state.counters["keys_in_show"] = kChannels * kKeysPerChannel;
}

/// The studio's whole answer to one pointer move of the drag, as the page sends it: the message
/// read, the edit applied, the show handed on, and what every client is sent back (bytes_out).
void BM_StudioDragStep(benchmark::State& state) {
  avar::rig::Rig rig;
  rig.name = "big";
  for (int c = 0; c < kChannels; ++c) {
    avar::rig::ChannelSpec spec;
    spec.name = "ch" + std::to_string(c);
    spec.min = -1000, spec.max = 1000, spec.rest = 0;
    rig.channels.push_back(spec);
  }
  avar::studio::Studio studio(rig, big_show(), "");
  const auto message = [](double sign) {
    std::string edits;
    for (int c = 0; c < kDraggedChannels; ++c) {
      std::string keys;
      for (int k = 0; k < kDraggedPerChannel; ++k) keys += (k ? "," : "") + std::to_string(500 + k);
      edits += std::string(c ? "," : "") + R"({"op":"move","channel":"ch)" + std::to_string(c * 4) + R"(","keys":[)" + keys +
               R"(],"dt":)" + std::to_string(sign * 0.001) + R"(,"dv":)" + std::to_string(sign * 0.1) + "}";
    }
    return R"({"type":"edit","continues":true,"edits":[)" + edits + "]}";
  };
  const std::string there = message(1), back = message(-1);
  bool forth = true;
  double bytes = 0;
  for (auto _ : state) {
    const avar::studio::Replies r = studio.handle(forth ? there : back);
    if (r.to_sender.find("\"ok\"") == std::string::npos) state.SkipWithError(r.to_sender.c_str());
    for (const std::string& m : r.to_all) bytes = static_cast<double>(m.size());
    forth = !forth;
  }
  state.counters["bytes_out"] = bytes;
}

void BM_UndoDragStep(benchmark::State& state) {
  ShowDocument doc = big_show();
  const std::vector<KeyEdit> there = drag_step(1);
  for (auto _ : state) {
    state.PauseTiming();
    doc.apply(there);
    state.ResumeTiming();
    doc.undo();
  }
}

/// A file of this run under the temporary directory.
std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("avar-bench-edit-" + std::to_string(::getpid()) + "-" + name)).string();
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void BM_RandomEditsUndoneAndRedone(benchmark::State& state) {
  const std::string original = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";
  const std::string edited = scratch("edited.yaml");
  const std::string start = scratch("start.yaml");
  const std::string end = scratch("end.yaml");
  double applied = 0, refused = 0, same_start = 1, same_end = 1;
  for (auto _ : state) {
    std::mt19937 rng(4711);
    ShowDocument doc = ShowDocument::open(original);
    for (int e = 0; e < 10000; ++e) {
      try {
        doc.apply(avar::testing::random_show_edit(rng, doc, 12));
        ++applied;
      } catch (const edit::EditError&) {
        ++refused;
      }
    }
    doc.save(edited);
    while (doc.undo()) {
    }
    doc.save(start);
    while (doc.redo()) {
    }
    doc.save(end);
    same_start = std::min(same_start, bytes_of(start) == bytes_of(original) ? 1.0 : 0.0);
    same_end = std::min(same_end, bytes_of(end) == bytes_of(edited) ? 1.0 : 0.0);
  }
  for (const std::string& path : {edited, start, end}) std::filesystem::remove(path);
  state.counters["edits_applied"] = benchmark::Counter(applied, benchmark::Counter::kAvgIterations);
  state.counters["edits_refused"] = benchmark::Counter(refused, benchmark::Counter::kAvgIterations);
  state.counters["identical_original"] = same_start;
  state.counters["identical_edited"] = same_end;
}

double worst(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

BENCHMARK(BM_DragThousandKeys)->Repetitions(10)->ComputeStatistics("worst", worst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StudioDragStep)->Repetitions(5)->ComputeStatistics("worst", worst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UndoDragStep)->Repetitions(10)->ComputeStatistics("worst", worst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RandomEditsUndoneAndRedone)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
