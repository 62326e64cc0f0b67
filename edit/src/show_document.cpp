#include "avar/edit/show_document.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "avar/config/feasibility.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/core/bit_cast.hpp"
#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"

namespace avar::edit {
namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0}, "cannot read the file");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
  out.flush();
  if (!out) throw InputError({path, 0, 0}, "cannot write the show file");
}

std::string group_label(std::span<const KeyEdit> edits) {
  if (edits.size() == 1) return describe(edits.front());
  return std::to_string(edits.size()) + " edits: " + describe(edits.front()) + ", ...";
}

bool same_optional(const std::optional<double>& a, const std::optional<double>& b) noexcept {
  return a.has_value() == b.has_value() && (!a || same_bits(*a, *b));
}

/// Every field the show file writes (not where it was read).
bool same_key(const playback::RawKey& a, const playback::RawKey& b) noexcept {
  return same_bits(a.time, b.time) && same_bits(a.value, b.value) && a.interpolation == b.interpolation &&
         playback::same_handle(a.left, b.left) && playback::same_handle(a.right, b.right) && a.left_type == b.left_type &&
         a.right_type == b.right_type && a.easing == b.easing && same_bits(a.back, b.back) &&
         same_bits(a.amplitude, b.amplitude) && same_bits(a.period, b.period) && same_optional(a.in_slope, b.in_slope) &&
         same_optional(a.out_slope, b.out_slope) && same_bits(a.tension, b.tension) && same_bits(a.continuity, b.continuity) &&
         same_bits(a.bias, b.bias);
}

/// Whether the curve-wide settings (written apart from the keys) are the same.
bool same_settings(const playback::RawCurve& a, const playback::RawCurve& b) noexcept {
  return a.extrapolation == b.extrapolation && a.auto_smoothing == b.auto_smoothing && a.cycles.before == b.cycles.before &&
         a.cycles.after == b.cycles.after && a.cycles.before_count == b.cycles.before_count &&
         a.cycles.after_count == b.cycles.after_count;
}

/// The stretch of keys that differs between `before` and `after`, with the key after it.
KeySplice splice_of(const std::string& channel, const std::vector<playback::RawKey>& before,
                    const std::vector<playback::RawKey>& after) {
  std::size_t head = 0;
  while (head < before.size() && head < after.size() && same_key(before[head], after[head])) ++head;
  std::size_t tail = 0;
  while (tail < before.size() - head && tail < after.size() - head &&
         same_key(before[before.size() - 1 - tail], after[after.size() - 1 - tail]))
    ++tail;
  if (head == before.size() && head == after.size()) return {channel, head, 0, 0};
  if (tail > 0) --tail;  // the first unchanged key after the stretch may be written differently
  return {channel, head, before.size() - head - tail, after.size() - head - tail};
}

}  // namespace

ShowDocument::ShowDocument(playback::Show show) : show_(std::move(show)) {}

ShowDocument ShowDocument::open(const std::string& path) {
  std::string bytes = read_bytes(path);
  ShowDocument document(config::load_show_text(bytes, path));
  document.opened_bytes_ = std::move(bytes);
  return document;
}

std::optional<std::size_t> ShowDocument::track_of(const std::string& channel) const {
  for (std::size_t i = 0; i < show_.tracks.size(); ++i)
    if (show_.tracks[i].channel == channel) return i;
  return std::nullopt;
}

void ShowDocument::apply(const KeyEdit& edit) { apply(std::span<const KeyEdit>(&edit, 1)); }

void ShowDocument::apply(std::span<const KeyEdit> edits) { apply(edits, false); }

void ShowDocument::continue_last(std::span<const KeyEdit> edits) { apply(edits, true); }

bool ShowDocument::continues_last(const Step& step) const {
  if (position_ == 0 || position_ != history_.size() || saved_position_ == position_) return false;
  const Step& last = history_.back();
  if (step.times_after || last.times_after || step.changes.size() != last.changes.size()) return false;
  for (const TrackChange& c : step.changes) {
    const auto same =
        std::find_if(last.changes.begin(), last.changes.end(), [&](const TrackChange& l) { return l.channel == c.channel; });
    if (same == last.changes.end() || !c.before || !c.after || !same->before || !same->after) return false;
  }
  return true;
}

void ShowDocument::apply(std::span<const KeyEdit> edits, bool continuing) {
  last_change_ = {};
  if (edits.empty()) throw EditError("no edit given");
  // Every edit applied in order to working copies of the keys of the channels it touches.
  struct Working {
    std::string channel;
    std::optional<playback::RawCurve> before;
    std::vector<playback::RawKey> keys;
    std::optional<double> audio_start;  ///< where a track's sound begins, rippled by time edits
  };
  std::vector<Working> touched;
  const auto working = [&](const std::string& channel) -> Working& {
    auto w = std::find_if(touched.begin(), touched.end(), [&](const Working& x) { return x.channel == channel; });
    if (w != touched.end()) return *w;
    Working fresh{channel, std::nullopt, {}, std::nullopt};
    if (const std::optional<std::size_t> i = track_of(channel)) {
      fresh.before = show_.tracks[*i].raw, fresh.keys = fresh.before->keys;
      if (fresh.before->audio) fresh.audio_start = fresh.before->audio->start_s;
    }
    touched.push_back(std::move(fresh));
    return touched.back();
  };
  const Times now{show_.duration, show_.cues, show_.markers};
  std::optional<Times> times;
  for (const KeyEdit& edit : edits) {
    if (const auto* markers = std::get_if<SetMarkers>(&edit)) {
      times = times ? *times : now;
      times->markers = checked_markers(*markers, times->duration);
      continue;
    }
    if (!is_time_edit(edit)) {
      Working& w = working(edited_channel(edit));
      w.keys = edited_keys(w.keys, edit, w.channel);
      continue;
    }
    times = rippled(times ? *times : now, edit);
    for (const playback::Track& t : show_.tracks) working(t.channel);
    for (Working& w : touched) {
      w.keys = edited_keys(w.keys, edit, w.channel);
      // A sound moves with the time around its start; cut out, it starts where the cut was.
      if (!w.audio_start) continue;
      const std::optional<double> start = rippled_time(*w.audio_start, edit);
      w.audio_start = start ? *start : std::max(0.0, std::get<DeleteTime>(edit).from);
    }
  }
  // Each changed curve built as playback builds it, before anything changes.
  Step step{group_label(edits), {}, std::nullopt, std::nullopt};
  if (times) step.times_before = now, step.times_after = times;
  std::vector<std::optional<playback::Curve>> built;  // the curves built here, committed below
  for (Working& w : touched) {
    TrackChange change{w.channel, 0, w.before, std::nullopt};
    built.emplace_back();
    if (!w.keys.empty()) {
      playback::RawCurve raw = w.before ? *w.before : playback::RawCurve({}, {show_.where.file, 0, 0});
      raw.keys = std::move(w.keys);
      if (raw.audio && w.audio_start) raw.audio->start_s = *w.audio_start;
      try {
        const std::optional<std::size_t> track = track_of(w.channel);
        built.back() = track ? playback::Curve::build(raw, show_.tracks[*track].curve, show_.tracks[*track].raw)
                             : playback::Curve::build(raw);
      } catch (const InputError& e) {
        throw EditError(step.label + ": " + w.channel + ": " + e.problem());
      }
      change.after = std::move(raw);
    }
    step.changes.push_back(std::move(change));
  }
  // Commit in order; each change's position is where its track is (or goes) at its turn.
  for (std::size_t i = 0; i < step.changes.size(); ++i) {
    TrackChange& change = step.changes[i];
    change.position = track_of(change.channel).value_or(show_.tracks.size());
    put(change, change.after, std::move(built[i]));
  }
  put(step.times_after);
  if (continuing && continues_last(step)) {
    // The last step keeps its before-state and takes this one's after-state.
    Step& last = history_.back();
    for (TrackChange& c : step.changes)
      std::find_if(last.changes.begin(), last.changes.end(), [&](const TrackChange& l) {
        return l.channel == c.channel;
      })->after = std::move(c.after);
    last.label = std::move(step.label);
    return;
  }
  push_step(std::move(step));
}

void ShowDocument::push_step(Step step) {
  history_.resize(position_);
  if (saved_position_ && *saved_position_ > position_) saved_position_.reset();
  history_.push_back(std::move(step));
  ++position_;
}

void ShowDocument::retime(const rig::Rig& rig) {
  last_change_ = {};
  if (show_.layered() || !show_.targets.empty())
    throw EditError(
        std::string("retime: this show has ") + (show_.layered() ? "layers" : "targets") +
        ", whose times a stretch would leave behind (retime with avar check --retime, or edit those times in the file)");
  const auto asks_too_much = [](const config::Infeasible& f) {
    return f.kind == config::Infeasible::Kind::speed || f.kind == config::Infeasible::Kind::acceleration;
  };
  const std::vector<config::Infeasible> found = config::check_feasibility(show_, rig);
  const auto spans = std::count_if(found.begin(), found.end(), asks_too_much);
  if (spans == 0) throw EditError("retime: no span asks more speed or acceleration than its channel allows");
  playback::Show retimed = config::retime(show_, rig);
  Step step{"retime " + std::to_string(spans) + " span" + (spans == 1 ? "" : "s") + " to the rig's limits (+" +
                format_number(retimed.duration - show_.duration) + " s)",
            {},
            Times{show_.duration, show_.cues, show_.markers},
            Times{retimed.duration, retimed.cues, retimed.markers}};
  // config::retime keeps the tracks and their order: every track is a change, its curve built.
  for (std::size_t i = 0; i < show_.tracks.size(); ++i) {
    step.changes.push_back({show_.tracks[i].channel, i, show_.tracks[i].raw, retimed.tracks[i].raw});
    put(step.changes.back(), step.changes.back().after, std::move(retimed.tracks[i].curve));
  }
  put(step.times_after);
  push_step(std::move(step));
}

void ShowDocument::put(const TrackChange& change, const std::optional<playback::RawCurve>& raw,
                       std::optional<playback::Curve> built) {
  const auto at = show_.tracks.begin() + static_cast<std::ptrdiff_t>(change.position);
  const bool exists = change.position < show_.tracks.size() && show_.tracks[change.position].channel == change.channel;
  if (!raw) {
    if (exists) show_.tracks.erase(at);
    last_change_.whole = true;
    return;
  }
  if (!exists || !same_settings(show_.tracks[change.position].raw, *raw)) last_change_.whole = true;
  else last_change_.splices.push_back(splice_of(change.channel, show_.tracks[change.position].raw.keys, raw->keys));
  // Undo and redo build again what built when the step was applied (history keeps keys only),
  // from the segments the step left alone.
  playback::Curve curve =
      built    ? std::move(*built)
      : exists ? playback::Curve::build(*raw, show_.tracks[change.position].curve, show_.tracks[change.position].raw)
               : playback::Curve::build(*raw);
  if (exists) {
    show_.tracks[change.position].raw = *raw;
    show_.tracks[change.position].curve = std::move(curve);
  } else {
    show_.tracks.insert(at, playback::Track{change.channel, *raw, std::move(curve), raw->where});
  }
}

void ShowDocument::put(const std::optional<Times>& times) {
  if (!times) return;
  last_change_.whole = true;
  show_.duration = times->duration;
  show_.cues = times->cues;
  show_.markers = times->markers;
}

ShowDocument::Times ShowDocument::rippled(const Times& times, const KeyEdit& edit) const {
  if (show_.layered() || !show_.targets.empty())
    throw EditError(describe(edit) + ": a time edit moves the show's tracks and cues; this show also has " +
                    (show_.layered() ? "layers" : "targets") +
                    ", whose times it would leave behind (edit those times in the file)");
  rippled_time(0, edit);  // checks the edit itself
  Times out{times.duration, {}, {}};
  if (const auto* insert = std::get_if<InsertTime>(&edit)) {
    if (insert->at <= times.duration) out.duration += insert->length;
  } else {
    const auto& cut = std::get<DeleteTime>(edit);
    out.duration -= std::max(0.0, std::min(cut.to, times.duration) - std::max(cut.from, 0.0));
    if (!(out.duration > playback::Curve::kKeySnap))
      throw EditError(describe(edit) + ": the show, " + format_number(times.duration) + " s long, would have no time left");
  }
  for (const playback::Cue& cue : times.cues) {
    const std::optional<double> t = rippled_time(cue.time, edit);
    if (!t) continue;
    out.cues.push_back(cue);
    out.cues.back().time = std::clamp(*t, 0.0, out.duration);
  }
  for (const playback::Marker& marker : times.markers) {
    const std::optional<double> t = rippled_time(marker.time, edit);
    if (!t) continue;
    out.markers.push_back(marker);
    out.markers.back().time = std::clamp(*t, 0.0, out.duration);
  }
  return out;
}

std::vector<playback::Marker> ShowDocument::checked_markers(const SetMarkers& edit, double duration) {
  std::vector<playback::Marker> out = edit.markers;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const playback::Marker& m = out[i];
    const std::string what = "set the markers: marker " + std::to_string(i + 1);
    if (!std::isfinite(m.time) || m.time < 0 || m.time > duration)
      throw EditError(what + " at " + format_number(m.time) + " s is outside the show (0 to " + format_number(duration) + " s)");
    if (m.name.empty()) throw EditError(what + " has no name");
    for (std::size_t j = 0; j < i; ++j)
      if (out[j].name == m.name) throw EditError(what + ": the name '" + m.name + "' is used twice");
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  return out;
}

bool ShowDocument::undo() {
  if (position_ == 0) return false;
  last_change_ = {};
  const Step& step = history_[--position_];
  for (auto c = step.changes.rbegin(); c != step.changes.rend(); ++c) put(*c, c->before);
  put(step.times_before);
  return true;
}

bool ShowDocument::redo() {
  if (position_ == history_.size()) return false;
  last_change_ = {};
  const Step& step = history_[position_++];
  for (const TrackChange& c : step.changes) put(c, c.after);
  put(step.times_after);
  return true;
}

std::string ShowDocument::undo_label() const { return position_ == 0 ? "" : history_[position_ - 1].label; }

std::string ShowDocument::redo_label() const { return position_ == history_.size() ? "" : history_[position_].label; }

void ShowDocument::save(const std::string& path) {
  if (position_ == 0 && opened_bytes_) {
    write_bytes(path, *opened_bytes_);
  } else {
    config::write_show_file(path, show_, "show '" + show_.name + "', saved by avar");
  }
  saved_position_ = position_;
}

}  // namespace avar::edit
