// Editing a show: key edits applied whole or refused whole, undo and redo, groups as one step,
// tracks made and removed, and saving (the opened bytes again for an unchanged show, the
// canonical form otherwise, read back to the same curves); a seeded family of random edits
// undone and redone to byte-identical files at each end.
#include "avar/edit/show_document.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "avar/config/feasibility.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "support/random_show_edits.hpp"
#include "support/temp_file.hpp"

namespace avar::edit {
namespace {

using playback::Interpolation;
using playback::RawKey;

const std::string kHelloHead = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const playback::Track& track(const ShowDocument& doc, const std::string& channel) {
  for (const playback::Track& t : doc.show().tracks)
    if (t.channel == channel) return t;
  throw std::invalid_argument("no track " + channel);
}

RawKey key_at(double t, double v, Interpolation i = Interpolation::linear) {
  RawKey k;
  k.time = t;
  k.value = v;
  k.interpolation = i;
  return k;
}

/// Every key's time and value of every track, and the tracks' order: what an edit may change.
std::vector<std::vector<std::pair<double, double>>> keys_of(const ShowDocument& doc) {
  std::vector<std::vector<std::pair<double, double>>> all;
  for (const playback::Track& t : doc.show().tracks) {
    all.emplace_back();
    for (const RawKey& k : t.raw.keys) all.back().emplace_back(k.time, k.value);
  }
  return all;
}

TEST(ShowDocument, AnUnchangedShowSavesTheBytesItWasOpenedFrom) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  EXPECT_FALSE(doc.modified());
  const std::string path = testing::temp_path("unchanged.yaml");
  doc.save(path);
  EXPECT_EQ(bytes_of(path), bytes_of(kHelloHead));
  EXPECT_FALSE(doc.modified());
}

TEST(ShowDocument, MovedKeysTakeTheirHandlesAndTheCurveFollows) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const RawKey before = track(doc, "lid_left").raw.keys[0];  // bezier, right handle [0.4, 20]
  ASSERT_TRUE(before.right);
  doc.apply(MoveKeys{"lid_left", {0}, -0.5, 3});
  const RawKey& after = track(doc, "lid_left").raw.keys[0];
  EXPECT_DOUBLE_EQ(after.time, before.time - 0.5);
  EXPECT_DOUBLE_EQ(after.value, before.value + 3);
  EXPECT_DOUBLE_EQ(after.right->time, before.right->time - 0.5);
  EXPECT_DOUBLE_EQ(after.right->value, before.right->value + 3);
  EXPECT_EQ(track(doc, "lid_left").curve.evaluate(before.time - 0.5), before.value + 3);
  EXPECT_TRUE(doc.modified());
  EXPECT_EQ(doc.undo_label(), "move 1 key of 'lid_left' by -0.5 s, +3");
}

TEST(ShowDocument, ARefusedEditChangesNothing) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const auto keys = keys_of(doc);
  const auto expect_refused = [&](const KeyEdit& edit, const std::string& says) {
    try {
      doc.apply(edit);
      ADD_FAILURE() << describe(edit) << " was applied";
    } catch (const EditError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_EQ(keys_of(doc), keys);
    EXPECT_EQ(doc.undo_steps(), 0u);
    EXPECT_FALSE(doc.modified());
  };
  // lid_left's keys are at 0, 1, 4, 4.08, ...
  expect_refused(MoveKeys{"lid_left", {2}, 0.1, 0}, "the move would put key 2 of 'lid_left' at 4.1 s and key 3 at 4.08 s");
  expect_refused(MoveKeys{"lid_left", {99}, 0.1, 0}, "no key 99 in 'lid_left', which has 10 key(s)");
  expect_refused(MoveKeys{"lid_left", {1, 1}, 0.1, 0}, "key 1 of 'lid_left' is given twice");
  expect_refused(MoveKeys{"lid_left", {1}, std::nan(""), 0}, "the time shift for 'lid_left' is not a finite number");
  expect_refused(AddKeys{"lid_left", {key_at(4.0, 1)}}, "a key of 'lid_left' is at 4 s already");
  expect_refused(SetKey{"lid_left", 1, key_at(0, 50)}, "the new time would put key 0 of 'lid_left' at 0 s and key 1 at 0 s");
  expect_refused(DeleteKeys{"lid_left", {}}, "no key of 'lid_left' given");
  expect_refused(AddKeys{"", {key_at(1, 1)}}, "an edit names no channel");
  // A key whose own fields do not build: the curve builder's words, named by the edit.
  RawKey free_without_handle = key_at(1, 95, Interpolation::bezier);
  free_without_handle.right_type = playback::HandleType::free;
  expect_refused(SetKey{"lid_left", 1, free_without_handle}, "set key 1 of 'lid_left'");
  // A group stops at its bad edit and changes nothing, the good edits before it included.
  EXPECT_THROW(doc.apply({MoveKeys{"jaw", {0}, 0, 1}, MoveKeys{"lid_left", {2}, 0.1, 0}}), EditError);
  EXPECT_EQ(keys_of(doc), keys);
  EXPECT_EQ(doc.undo_steps(), 0u);
}

TEST(ShowDocument, UndoAndRedoStepThroughTheHistoryAndANewEditDropsTheRedo) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const auto k0 = keys_of(doc);
  doc.apply(MoveKeys{"jaw", {1}, 0, 2});
  const auto k1 = keys_of(doc);
  doc.apply(DeleteKeys{"jaw", {2}});
  const auto k2 = keys_of(doc);
  EXPECT_EQ(doc.undo_steps(), 2u);
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(keys_of(doc), k1);
  EXPECT_EQ(doc.redo_label(), "delete 1 key of 'jaw'");
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(keys_of(doc), k0);
  EXPECT_FALSE(doc.modified());
  EXPECT_FALSE(doc.undo());
  EXPECT_TRUE(doc.redo());
  EXPECT_TRUE(doc.redo());
  EXPECT_EQ(keys_of(doc), k2);
  EXPECT_FALSE(doc.redo());
  doc.undo();
  doc.apply(MoveKeys{"jaw", {0}, 0, 1});
  EXPECT_EQ(doc.redo_steps(), 0u);
  EXPECT_EQ(doc.undo_steps(), 2u);
}

TEST(ShowDocument, AGroupIsOneStep) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const auto k0 = keys_of(doc);
  doc.apply({MoveKeys{"lid_left", {1}, 0, -5}, MoveKeys{"lid_right", {1}, 0, -5}, MoveKeys{"lid_left", {1}, 0, -5}});
  EXPECT_DOUBLE_EQ(track(doc, "lid_left").raw.keys[1].value, 85);
  EXPECT_DOUBLE_EQ(track(doc, "lid_right").raw.keys[1].value, 90);
  EXPECT_EQ(doc.undo_steps(), 1u);
  doc.undo();
  EXPECT_EQ(keys_of(doc), k0);
}

TEST(ShowDocument, ADragIsOneUndoStepHoweverManyMovesItHas) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const auto k0 = keys_of(doc);
  doc.apply(MoveKeys{"jaw", {1}, 0, 1});
  const auto k1 = keys_of(doc);
  // A drag over two tracks: its first move a step of its own, then 30 moves continuing it.
  const std::vector<KeyEdit> move = {MoveKeys{"neck_pan", {2}, 0.001, 0.5}, MoveKeys{"neck_tilt", {1}, 0, -0.5}};
  doc.apply(move);
  for (int i = 0; i < 30; ++i) doc.continue_last(move);
  EXPECT_EQ(doc.undo_steps(), 2u);
  EXPECT_NEAR(track(doc, "neck_pan").raw.keys[2].value, 40 + 31 * 0.5, 1e-9);
  const auto dragged = keys_of(doc);
  doc.undo();
  EXPECT_EQ(keys_of(doc), k1);  // the whole drag undone at once
  doc.redo();
  EXPECT_EQ(keys_of(doc), dragged);

  // A move of other tracks, a time edit, or a continuation after a save starts a step of its own.
  doc.continue_last({MoveKeys{"jaw", {2}, 0, 1}});
  EXPECT_EQ(doc.undo_steps(), 3u);
  doc.save(testing::temp_path("dragged.yaml"));
  doc.continue_last({MoveKeys{"jaw", {2}, 0, 1}});
  EXPECT_EQ(doc.undo_steps(), 4u);
  EXPECT_TRUE(doc.modified());
  doc.continue_last({InsertTime{1, 1}});
  doc.continue_last({InsertTime{1, 1}});
  EXPECT_EQ(doc.undo_steps(), 6u);
  while (doc.undo()) {
  }
  EXPECT_EQ(keys_of(doc), k0);
}

TEST(ShowDocument, TracksAreMadeAndRemovedAndComeBackInPlace) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const std::size_t tracks = doc.show().tracks.size();
  doc.apply(AddKeys{"spare", {key_at(2, 10), key_at(1, 5)}});
  ASSERT_EQ(doc.show().tracks.size(), tracks + 1);
  EXPECT_EQ(track(doc, "spare").raw.keys.size(), 2u);
  EXPECT_EQ(track(doc, "spare").raw.keys[0].time, 1);  // in time order
  EXPECT_DOUBLE_EQ(track(doc, "spare").curve.evaluate(1.5), 7.5);

  const std::string first = doc.show().tracks[0].channel;
  std::vector<std::size_t> all(doc.show().tracks[0].raw.keys.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  doc.apply(DeleteKeys{first, all});
  EXPECT_EQ(doc.show().tracks.size(), tracks);
  EXPECT_NE(doc.show().tracks[0].channel, first);
  doc.undo();
  EXPECT_EQ(doc.show().tracks[0].channel, first);
  doc.undo();
  EXPECT_EQ(doc.show().tracks.size(), tracks);
}

TEST(ShowDocument, AnEditedShowSavesTheCanonicalFormThatReadsBackToTheSameCurves) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  doc.apply(MoveKeys{"neck_pan", {1, 2}, 0.05, -4});
  const std::string path = testing::temp_path("edited.yaml");
  doc.save(path);
  EXPECT_FALSE(doc.modified());
  const playback::Show again = config::load_show_file(path);
  ASSERT_EQ(again.tracks.size(), doc.show().tracks.size());
  for (std::size_t i = 0; i < again.tracks.size(); ++i)
    for (double t = -1; t < 13; t += 0.0137)
      ASSERT_EQ(again.tracks[i].curve.evaluate(t), doc.show().tracks[i].curve.evaluate(t))
          << again.tracks[i].channel << " at " << t;
  EXPECT_TRUE(doc.undo());
  EXPECT_TRUE(doc.modified());
}

TEST(ShowDocument, SavingToAFolderThatIsNotThereNamesThePath) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  try {
    doc.save("/nonexistent/dir/show.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/show.yaml"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(doc.modified());
}

TEST(ShowDocument, InsertingTimeMovesEveryLaterKeyAndCueAndDeletingCutsThemOut) {
  ShowDocument doc = ShowDocument::open(AVAR_SOURCE_DIR "/examples/shows/stage-lights.yaml");
  const playback::Show before = doc.show();
  const auto k0 = keys_of(doc);
  doc.apply(InsertTime{2.0, 0.5});
  EXPECT_DOUBLE_EQ(doc.show().duration, before.duration + 0.5);
  for (std::size_t t = 0; t < before.tracks.size(); ++t)
    for (std::size_t k = 0; k < before.tracks[t].raw.keys.size(); ++k) {
      const RawKey& was = before.tracks[t].raw.keys[k];
      const RawKey& now = doc.show().tracks[t].raw.keys[k];
      EXPECT_DOUBLE_EQ(now.time, was.time >= 2.0 ? was.time + 0.5 : was.time) << before.tracks[t].channel << " key " << k;
      EXPECT_EQ(now.value, was.value);
    }
  ASSERT_EQ(doc.show().cues.size(), before.cues.size());
  for (std::size_t c = 0; c < before.cues.size(); ++c)
    EXPECT_DOUBLE_EQ(doc.show().cues[c].time, before.cues[c].time >= 2.0 ? before.cues[c].time + 0.5 : before.cues[c].time);
  EXPECT_EQ(doc.undo_label(), "insert 0.5 s at 2 s");

  // Cutting the inserted span out again gives the show back, key for key (to the rounding of
  // adding and taking 0.5 s).
  doc.apply(DeleteTime{2.0, 2.5});
  EXPECT_DOUBLE_EQ(doc.show().duration, before.duration);
  const auto k2 = keys_of(doc);
  ASSERT_EQ(k2.size(), k0.size());
  for (std::size_t t = 0; t < k0.size(); ++t) {
    ASSERT_EQ(k2[t].size(), k0[t].size());
    for (std::size_t k = 0; k < k0[t].size(); ++k) {
      EXPECT_NEAR(k2[t][k].first, k0[t][k].first, 1e-12);
      EXPECT_EQ(k2[t][k].second, k0[t][k].second);
    }
  }
  doc.undo();
  doc.undo();
  EXPECT_EQ(keys_of(doc), k0);
  EXPECT_EQ(doc.show().duration, before.duration);
  EXPECT_FALSE(doc.modified());

  // A cut over keys deletes them; a cut of the whole show is refused.
  doc.apply(DeleteTime{2.4, 2.8});  // the strobe's cues at 2.5 and 2.7 s
  EXPECT_DOUBLE_EQ(doc.show().duration, before.duration - 0.4);
  EXPECT_LT(doc.show().cues.size(), before.cues.size());
  EXPECT_THROW(doc.apply(DeleteTime{-1, before.duration + 1}), EditError);
  EXPECT_THROW(doc.apply(InsertTime{1, 0}), EditError);
  EXPECT_THROW(doc.apply(InsertTime{std::nan(""), 1}), EditError);
}

TEST(ShowDocument, MarkersAreSetAsOneUndoStepAndMoveWithTheTimeAroundThem) {
  ShowDocument doc = ShowDocument::open(AVAR_SOURCE_DIR "/examples/shows/stage-lights.yaml");
  ASSERT_EQ(doc.show().markers.size(), 2u);  // scream at 2.4 s, quiet at 3.6 s
  // Add one (out of order: kept sorted), rename one, in one step.
  doc.apply(SetMarkers{{{2.4, "scream!", {}}, {3.6, "quiet", {}}, {1.0, "intro", {}}}});
  ASSERT_EQ(doc.show().markers.size(), 3u);
  EXPECT_EQ(doc.show().markers[0].name, "intro");
  EXPECT_EQ(doc.show().markers[1].name, "scream!");
  EXPECT_EQ(doc.undo_label(), "set the markers (3 markers)");
  EXPECT_TRUE(doc.last_change().whole);
  // Time edits carry them: an insert before moves them, a cut over one deletes it.
  doc.apply(InsertTime{2.0, 0.5});
  EXPECT_DOUBLE_EQ(doc.show().markers[1].time, 2.9);
  EXPECT_DOUBLE_EQ(doc.show().markers[0].time, 1.0);
  doc.apply(DeleteTime{2.8, 3.0});
  ASSERT_EQ(doc.show().markers.size(), 2u);
  EXPECT_EQ(doc.show().markers[1].name, "quiet");
  // Bad lists change nothing.
  const std::size_t steps = doc.undo_steps();
  EXPECT_THROW(doc.apply(SetMarkers{{{1, "a", {}}, {2, "a", {}}}}), EditError);
  EXPECT_THROW(doc.apply(SetMarkers{{{-1, "a", {}}}}), EditError);
  EXPECT_THROW(doc.apply(SetMarkers{{{1, "", {}}}}), EditError);
  EXPECT_THROW(doc.apply(SetMarkers{{{std::nan(""), "a", {}}}}), EditError);
  EXPECT_EQ(doc.undo_steps(), steps);
  // Undone to the start, the file saves as it was opened.
  while (doc.undo()) {
  }
  EXPECT_EQ(doc.show().markers.size(), 2u);
  EXPECT_EQ(doc.show().markers[0].name, "scream");
  EXPECT_FALSE(doc.modified());
  // A show with targets takes markers too (no time of its moves).
  ShowDocument targets = ShowDocument::open(AVAR_SOURCE_DIR "/examples/shows/look-around.yaml");
  targets.apply(SetMarkers{{{8.4, "speaks", {}}}});
  EXPECT_EQ(targets.show().markers.size(), 1u);
}

TEST(ShowDocument, ATimeEditIsRefusedWhereItWouldLeaveLayersOrTargetsBehind) {
  ShowDocument doc = ShowDocument::open(AVAR_SOURCE_DIR "/examples/shows/look-around.yaml");
  ASSERT_FALSE(doc.show().targets.empty());
  try {
    doc.apply(InsertTime{1, 1});
    FAIL();
  } catch (const EditError& e) {
    EXPECT_NE(std::string(e.what()).find("this show also has targets"), std::string::npos) << e.what();
  }
  EXPECT_EQ(doc.undo_steps(), 0u);
}

TEST(ShowDocument, RetimeStretchesWhatAsksTooMuchAsOneUndoStep) {
  ShowDocument doc = ShowDocument::open(kHelloHead);
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  // Nothing in the bundled show asks too much of the head.
  EXPECT_THROW(doc.retime(rig), EditError);
  EXPECT_EQ(doc.undo_steps(), 0u);
  // The jaw's key at 8 s (25 deg) moved to 7.85 s, 0.05 s after its 2 deg key: 460 deg/s, and
  // the jaw allows 300.
  doc.apply(MoveKeys{"jaw", {8}, -0.15, 0});
  const double duration = doc.show().duration;
  const auto before = keys_of(doc);
  ASSERT_FALSE(config::check_feasibility(doc.show(), rig).empty());
  doc.retime(rig);
  EXPECT_EQ(doc.undo_steps(), 2u);
  EXPECT_EQ(doc.undo_label().rfind("retime ", 0), 0u) << doc.undo_label();
  EXPECT_GT(doc.show().duration, duration);
  for (const config::Infeasible& f : config::check_feasibility(doc.show(), rig))
    EXPECT_TRUE(f.kind == config::Infeasible::Kind::jump || f.kind == config::Infeasible::Kind::range) << f.to_string();
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(keys_of(doc), before);
  EXPECT_EQ(doc.show().duration, duration);
  ASSERT_TRUE(doc.redo());
  EXPECT_GT(doc.show().duration, duration);
}

TEST(ShowDocument, RandomEditsUndoneAndRedoneSaveTheSameBytesAtEachEnd) {
  const unsigned seed = 8675309;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  ShowDocument doc = ShowDocument::open(kHelloHead);
  std::size_t applied = 0, refused = 0;
  for (int e = 0; e < 2000; ++e) {
    try {
      doc.apply(testing::random_show_edit(rng, doc, 12));
      ++applied;
    } catch (const EditError&) {
      ++refused;
    }
  }
  EXPECT_EQ(doc.undo_steps(), applied);
  EXPECT_GT(applied, 1500u);
  const std::string edited = testing::temp_path("random-edited.yaml");
  doc.save(edited);
  const auto edited_keys = keys_of(doc);

  while (doc.undo()) {
  }
  EXPECT_FALSE(doc.modified() && doc.undo_steps() != 0);
  const std::string original = testing::temp_path("random-original.yaml");
  doc.save(original);
  EXPECT_EQ(bytes_of(original), bytes_of(kHelloHead));

  while (doc.redo()) {
  }
  EXPECT_EQ(keys_of(doc), edited_keys);
  const std::string again = testing::temp_path("random-again.yaml");
  doc.save(again);
  EXPECT_EQ(bytes_of(again), bytes_of(edited));
  std::cout << "seed " << seed << ": " << applied << " edits applied, " << refused << " refused\n";
}

/// A copy of every track's keys: what a client holds.
std::map<std::string, std::vector<RawKey>> client_copy(const ShowDocument& doc) {
  std::map<std::string, std::vector<RawKey>> copy;
  for (const playback::Track& t : doc.show().tracks) copy[t.channel] = t.raw.keys;
  return copy;
}

TEST(ShowDocument, EachChangeNamesTheKeysItChangedAndTheCurvesStayFreshBuilds) {
  // A client that applies every change's splices (or takes the whole show when told) holds the
  // document's keys at every step, edits, undos and redos alike; and the curves the document
  // rebuilt from their unchanged segments sample as Curve::build's.
  const unsigned seed = 1206;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  ShowDocument doc = ShowDocument::open(kHelloHead);
  auto client = client_copy(doc);
  std::size_t spliced = 0, whole = 0;
  const auto follow = [&] {
    const DocumentChange& change = doc.last_change();
    if (change.whole) {
      client = client_copy(doc), ++whole;
      return;
    }
    for (const KeySplice& k : change.splices) {
      std::vector<RawKey>& keys = client.at(k.channel);
      ASSERT_LE(k.from + k.removed, keys.size());
      const std::vector<RawKey>& now = track(doc, k.channel).raw.keys;
      keys.erase(keys.begin() + static_cast<std::ptrdiff_t>(k.from),
                 keys.begin() + static_cast<std::ptrdiff_t>(k.from + k.removed));
      keys.insert(keys.begin() + static_cast<std::ptrdiff_t>(k.from), now.begin() + static_cast<std::ptrdiff_t>(k.from),
                  now.begin() + static_cast<std::ptrdiff_t>(k.from + k.added));
      ++spliced;
    }
    for (const playback::Track& t : doc.show().tracks) {
      ASSERT_EQ(client.at(t.channel).size(), t.raw.keys.size()) << t.channel;
      for (std::size_t i = 0; i < t.raw.keys.size(); ++i) {
        ASSERT_EQ(client.at(t.channel)[i].time, t.raw.keys[i].time) << t.channel << " key " << i;
        ASSERT_EQ(client.at(t.channel)[i].value, t.raw.keys[i].value) << t.channel << " key " << i;
      }
      const playback::Curve fresh = playback::Curve::build(t.raw);
      for (double x = -1; x < 13; x += 0.0173) ASSERT_EQ(t.curve.evaluate(x), fresh.evaluate(x)) << t.channel << " at " << x;
    }
  };
  for (int e = 0; e < 300; ++e) {
    try {
      doc.apply(testing::random_show_edit(rng, doc, 12));
    } catch (const EditError&) {
      EXPECT_FALSE(doc.last_change().whole);
      EXPECT_TRUE(doc.last_change().splices.empty());
      continue;
    }
    follow();
    if (rng() % 4 == 0 && doc.undo()) follow();
    if (rng() % 8 == 0 && doc.redo()) follow();
  }
  EXPECT_GT(spliced, 100u);
  EXPECT_GT(whole, 10u);
}

}  // namespace
}  // namespace avar::edit
