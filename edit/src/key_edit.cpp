#include "avar/edit/key_edit.hpp"

#include <algorithm>
#include <cmath>

#include "avar/core/format.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace avar::edit {
namespace {

using playback::RawKey;

std::string quoted(const std::string& channel) { return "'" + channel + "'"; }

std::string seconds(double t) { return format_number(t) + " s"; }

/// The indices sorted, each once and in range; EditError otherwise.
std::vector<std::size_t> checked_indices(std::vector<std::size_t> indices, std::size_t count, const std::string& channel) {
  if (indices.empty()) throw EditError("no key of " + quoted(channel) + " given; expected at least one key index");
  std::sort(indices.begin(), indices.end());
  if (const auto twice = std::adjacent_find(indices.begin(), indices.end()); twice != indices.end())
    throw EditError("key " + std::to_string(*twice) + " of " + quoted(channel) + " is given twice");
  if (indices.back() >= count)
    throw EditError("no key " + std::to_string(indices.back()) + " in " + quoted(channel) + ", which has " +
                    std::to_string(count) + " key(s); expected an index from 0");
  return indices;
}

void check_finite(double x, const std::string& what, const std::string& channel) {
  if (!std::isfinite(x)) throw EditError(what + " for " + quoted(channel) + " is not a finite number");
}

void shift(RawKey& k, double dt, double dv) {
  k.time += dt;
  k.value += dv;
  for (std::optional<playback::Handle>* h : {&k.left, &k.right})
    if (*h) (*h)->time += dt, (*h)->value += dv;
}

/// Keys in time order, no two within the key snap of each other: the first pair that is not.
void check_order(const std::vector<RawKey>& keys, const std::string& channel, const char* what) {
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (!(keys[i].time - keys[i - 1].time > playback::Curve::kKeySnap))
      throw EditError(std::string(what) + " would put key " + std::to_string(i - 1) + " of " + quoted(channel) + " at " +
                      seconds(keys[i - 1].time) + " and key " + std::to_string(i) + " at " + seconds(keys[i].time) +
                      "; keys keep their order (a key may not reach or pass its neighbour)");
}

std::vector<RawKey> add(const std::vector<RawKey>& keys, const AddKeys& e) {
  if (e.keys.empty()) throw EditError("no key to add to " + quoted(e.channel));
  for (const RawKey& k : e.keys) {
    check_finite(k.time, "a new key's time", e.channel);
    check_finite(k.value, "a new key's value", e.channel);
  }
  std::vector<RawKey> out = keys;
  out.insert(out.end(), e.keys.begin(), e.keys.end());
  std::stable_sort(out.begin(), out.end(), [](const RawKey& a, const RawKey& b) { return a.time < b.time; });
  for (std::size_t i = 1; i < out.size(); ++i)
    if (!(out[i].time - out[i - 1].time > playback::Curve::kKeySnap))
      throw EditError("a key of " + quoted(e.channel) + " is at " + seconds(out[i - 1].time) + " already; move or replace it");
  return out;
}

std::vector<RawKey> remove(const std::vector<RawKey>& keys, const DeleteKeys& e) {
  const std::vector<std::size_t> gone = checked_indices(e.keys, keys.size(), e.channel);
  std::vector<RawKey> out;
  out.reserve(keys.size() - gone.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!std::binary_search(gone.begin(), gone.end(), i)) out.push_back(keys[i]);
  return out;
}

std::vector<RawKey> move(const std::vector<RawKey>& keys, const MoveKeys& e) {
  check_finite(e.dt, "the time shift", e.channel);
  check_finite(e.dv, "the value shift", e.channel);
  const std::vector<std::size_t> moved = checked_indices(e.keys, keys.size(), e.channel);
  std::vector<RawKey> out = keys;
  for (const std::size_t i : moved) {
    shift(out[i], e.dt, e.dv);
    check_finite(out[i].time, "a moved key's time", e.channel);
    check_finite(out[i].value, "a moved key's value", e.channel);
  }
  check_order(out, e.channel, "the move");
  return out;
}

std::vector<RawKey> set(const std::vector<RawKey>& keys, const SetKey& e) {
  checked_indices({e.key}, keys.size(), e.channel);
  check_finite(e.value.time, "the key's time", e.channel);
  check_finite(e.value.value, "the key's value", e.channel);
  std::vector<RawKey> out = keys;
  out[e.key] = e.value;
  check_order(out, e.channel, "the new time");
  return out;
}

void check_time_edit(const InsertTime& e) {
  if (!std::isfinite(e.at) || !std::isfinite(e.length) || !(e.length > 0))
    throw EditError("inserting time needs a finite time and a length above 0 s; found " + format_number(e.length) + " s at " +
                    format_number(e.at) + " s");
}

void check_time_edit(const DeleteTime& e) {
  if (!std::isfinite(e.from) || !std::isfinite(e.to) || !(e.to > e.from))
    throw EditError("deleting time needs a finite span that ends after it starts; found " + format_number(e.from) + " to " +
                    format_number(e.to) + " s");
}

std::vector<RawKey> ripple(const std::vector<RawKey>& keys, const KeyEdit& edit, const std::string& channel) {
  std::vector<RawKey> out;
  for (const RawKey& k : keys) {
    const std::optional<double> t = rippled_time(k.time, edit);
    if (!t) continue;
    RawKey moved = k;
    shift(moved, *t - k.time, 0);
    out.push_back(moved);
  }
  check_order(out, channel, "the time edit");
  return out;
}

std::string key_count(std::size_t n) { return n == 1 ? "1 key" : std::to_string(n) + " keys"; }

std::string signed_number(double x) { return (x >= 0 ? "+" : "") + format_number(x); }

}  // namespace

bool is_time_edit(const KeyEdit& edit) {
  return std::holds_alternative<InsertTime>(edit) || std::holds_alternative<DeleteTime>(edit);
}

const std::string& edited_channel(const KeyEdit& edit) {
  static const std::string every;  // a time edit's: every channel
  return std::visit(
      [](const auto& e) -> const std::string& {
        if constexpr (requires { e.channel; }) return e.channel;
        else return every;
      },
      edit);
}

std::optional<double> rippled_time(double t, const KeyEdit& time_edit) {
  // A time within the key snap of the edit's point counts as at it.
  constexpr double snap = playback::Curve::kKeySnap;
  if (const auto* insert = std::get_if<InsertTime>(&time_edit)) {
    check_time_edit(*insert);
    return t >= insert->at - snap ? t + insert->length : t;
  }
  const auto& cut = std::get<DeleteTime>(time_edit);
  check_time_edit(cut);
  if (t < cut.from - snap) return t;
  if (t < cut.to - snap) return std::nullopt;
  return t - (cut.to - cut.from);
}

std::string describe(const KeyEdit& edit) {
  struct Describe {
    std::string operator()(const AddKeys& e) const { return "add " + key_count(e.keys.size()) + " to " + quoted(e.channel); }
    std::string operator()(const DeleteKeys& e) const {
      return "delete " + key_count(e.keys.size()) + " of " + quoted(e.channel);
    }
    std::string operator()(const MoveKeys& e) const {
      return "move " + key_count(e.keys.size()) + " of " + quoted(e.channel) + " by " + seconds(e.dt) + ", " +
             signed_number(e.dv);
    }
    std::string operator()(const InsertTime& e) const { return "insert " + seconds(e.length) + " at " + seconds(e.at); }
    std::string operator()(const DeleteTime& e) const {
      return "delete the time from " + seconds(e.from) + " to " + seconds(e.to);
    }
    std::string operator()(const SetKey& e) const {
      return "set key " + std::to_string(e.key) + " of " + quoted(e.channel) + " (" + seconds(e.value.time) + ", " +
             format_number(e.value.value) + ", " + playback::to_string(e.value.interpolation) + ")";
    }
    std::string operator()(const SetMarkers& e) const {
      return "set the markers (" + std::to_string(e.markers.size()) + (e.markers.size() == 1 ? " marker)" : " markers)");
    }
  };
  return std::visit(Describe{}, edit);
}

std::vector<RawKey> edited_keys(const std::vector<RawKey>& keys, const KeyEdit& edit, const std::string& channel) {
  if (is_time_edit(edit)) return ripple(keys, edit, channel);
  struct Apply {
    const std::vector<RawKey>& keys;
    std::vector<RawKey> operator()(const AddKeys& e) const { return add(keys, e); }
    std::vector<RawKey> operator()(const DeleteKeys& e) const { return remove(keys, e); }
    std::vector<RawKey> operator()(const MoveKeys& e) const { return move(keys, e); }
    std::vector<RawKey> operator()(const SetKey& e) const { return set(keys, e); }
    std::vector<RawKey> operator()(const InsertTime&) const { return keys; }  // rippled above
    std::vector<RawKey> operator()(const DeleteTime&) const { return keys; }
    std::vector<RawKey> operator()(const SetMarkers&) const { return keys; }  // no keys: ShowDocument sets them
  };
  if (edited_channel(edit).empty()) throw EditError("an edit names no channel");
  return std::visit(Apply{keys}, edit);
}

}  // namespace avar::edit
