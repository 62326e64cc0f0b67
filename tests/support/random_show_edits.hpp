#pragma once
// Seeded random edits of a show being edited, as a user makes them in the studio: add a key (a
// paste), move one, replace one (a typed value, another interpolation, another handle type),
// delete one, insert or delete time. The edit-model tests and the edit benchmark share them.
// Some are refused by the model (a move past a neighbour): callers count those.

#include <random>

#include "avar/edit/show_document.hpp"

namespace avar::testing {

inline playback::RawKey random_key_at(double t, double v) {
  playback::RawKey k;
  k.time = t;
  k.value = v;
  return k;
}

/// One random edit of `doc`'s show, within `span_s` seconds of show time.
inline edit::KeyEdit random_show_edit(std::mt19937& rng, const edit::ShowDocument& doc, double span_s) {
  std::uniform_real_distribution<double> u(0, 1);
  if (doc.show().tracks.empty()) return edit::AddKeys{"jaw", {random_key_at(span_s * u(rng), 0)}};
  const playback::Track& t = doc.show().tracks[rng() % doc.show().tracks.size()];
  const std::size_t n = t.raw.keys.size();
  const std::size_t i = rng() % n;
  switch (rng() % 7) {
    case 0: return edit::AddKeys{t.channel, {random_key_at(-1 + (span_s + 2) * u(rng), -10 + 20 * u(rng))}};
    case 1: return edit::MoveKeys{t.channel, {i}, -0.2 + 0.4 * u(rng), -5 + 10 * u(rng)};
    case 2: {
      playback::RawKey k = t.raw.keys[i];
      k.value = -10 + 20 * u(rng);
      k.interpolation = static_cast<playback::Interpolation>(rng() % 3);
      k.left.reset(), k.right.reset();
      k.left_type = k.right_type = rng() % 2 ? playback::HandleType::automatic : playback::HandleType::vector;
      return edit::SetKey{t.channel, i, k};
    }
    case 3:
      if (n > 2) return edit::DeleteKeys{t.channel, {i}};
      return edit::MoveKeys{t.channel, {i}, 0, -1 + 2 * u(rng)};
    case 4: return edit::MoveKeys{t.channel, {i}, 0, -1 + 2 * u(rng)};
    case 5: return edit::InsertTime{span_s * u(rng), 0.01 + 0.5 * u(rng)};
    default: {
      const double from = span_s * u(rng);
      return edit::DeleteTime{from, from + 0.01 + 0.3 * u(rng)};
    }
  }
}

}  // namespace avar::testing
