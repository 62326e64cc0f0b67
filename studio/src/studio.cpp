#include "avar/studio/studio.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <utility>
#include <variant>

#include "avar/config/audio_file.hpp"
#include "avar/config/feasibility.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/raw_curve_codec.hpp"
#include "avar/studio/protocol.hpp"
#include "rig_json.hpp"

#include <filesystem>

namespace avar::studio {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxRefusedKept = 64;
/// The waveform's resolution: a low and a high sample per 10 ms of sound (a pixel at the dope
/// sheet's closest useful zoom), to 4 decimals.
constexpr double kWaveformBucket_s = 0.01;

std::string error_reply(std::string_view request, const std::string& problem) {
  return json{{"type", "error"}, {"request", request}, {"message", problem}}.dump();
}

std::string ok_reply(std::string_view request) { return json{{"type", "ok"}, {"request", request}}.dump(); }

/// The message type a client sent, for naming it in a reply ("" when it is not readable).
std::string request_type(std::string_view message) {
  const json j = json::parse(message, nullptr, false);
  if (j.is_object() && j.contains("type") && j["type"].is_string()) return j["type"].get<std::string>();
  return "";
}

}  // namespace

Studio::Studio(const rig::Rig& rig, edit::ShowDocument document, std::string show_path)
    : rig_(rig),
      document_(std::move(document)),
      show_path_(std::move(show_path)),
      initial_(std::make_shared<const playback::Show>(document_.show())),
      playing_(initial_) {
  for (const rig::ChannelSpec& c : rig.channels) channel_names_.push_back(c.name);
  // No edit adds, removes or reorders targets (time edits and retime refuse a show with them).
  for (const playback::TargetTrack& t : document_.show().targets) target_names_.push_back(t.effector);
}

void Studio::attach(session::ShowSession* session) {
  const std::lock_guard lock(mutex_);
  session_ = session;
}

std::string Studio::state_fields() const {
  const std::string fields = json{
      {"version", version_},
      {"file", show_path_.empty() ? json(nullptr) : json(show_path_)},
      {"modified", document_.modified()},
      {"undo", document_.undo_label()},
      {"redo",
       document_.redo_label()}}.dump();
  return fields.substr(1, fields.size() - 2);
}

std::string Studio::show_fields() const {
  // The show's JSON is spliced in as the writer wrote it: numbers that read back to the same
  // doubles.
  return state_fields() + ",\"show\":" + config::show_json(document_.show());
}

std::string Studio::show_message() const { return "{\"type\":\"show\"," + show_fields() + "}"; }

std::string Studio::change_message() const {
  const edit::DocumentChange& change = document_.last_change();
  if (change.whole) return show_message();
  // The keys are spliced in as the show writer writes them (numbers that read back the same).
  std::string splices;
  for (const edit::KeySplice& k : change.splices) {
    const playback::Show& show = document_.show();
    const auto track =
        std::find_if(show.tracks.begin(), show.tracks.end(), [&](const playback::Track& t) { return t.channel == k.channel; });
    std::string fields = json{{"channel", k.channel}, {"from", k.from}, {"remove", k.removed}}.dump();
    fields.pop_back();
    splices += (splices.empty() ? "" : ",") + fields + ",\"keys\":" + config::keys_json(track->raw, k.from, k.added) + "}";
  }
  return "{\"type\":\"keys\"," + state_fields() + ",\"tracks\":[" + splices + "]}";
}

std::string Studio::curves_message(const std::optional<std::vector<std::string>>& channels) const {
  json tracks = json::object();
  for (const playback::Track& t : document_.show().tracks)
    if (!channels || std::find(channels->begin(), channels->end(), t.channel) != channels->end())
      tracks[t.channel] = playback::encode_raw_curve(t.raw);
  return json{{"type", "curves"}, {"version", version_}, {"format", playback::kRawCurveFormat}, {"tracks", tracks}}.dump();
}

std::string Studio::check_message() const {
  json findings = json::array();
  for (const config::Infeasible& f : config::check_feasibility(document_.show(), rig_)) {
    const char* kind = f.kind == config::Infeasible::Kind::speed          ? "speed"
                       : f.kind == config::Infeasible::Kind::acceleration ? "acceleration"
                       : f.kind == config::Infeasible::Kind::range        ? "range"
                                                                          : "jump";
    findings.push_back({{"kind", kind},
                        {"channel", f.channel},
                        {"unit", f.unit},
                        {"t0", f.t0},
                        {"t1", f.t1},
                        {"required", f.required},
                        {"allowed", f.allowed},
                        {"text", f.to_string()}});
  }
  return json{{"type", "check"}, {"version", version_}, {"findings", findings}}.dump();
}

std::string Studio::waveform_message() const {
  json tracks = json::array();
  for (const playback::Track& t : document_.show().tracks) {
    if (!t.raw.audio) continue;
    const config::MonoAudio audio = config::read_mono_audio(t.raw.audio->path, t.where);
    json peaks = json::array();
    for (const float x : config::audio_peaks(audio, kWaveformBucket_s)) peaks.push_back(std::round(x * 1e4) / 1e4);
    tracks.push_back({{"channel", t.channel},
                      {"file", t.raw.audio->path},
                      {"start", t.raw.audio->start_s},
                      {"duration", audio.duration_s()},
                      {"bucket", kWaveformBucket_s},
                      {"peaks", std::move(peaks)}});
  }
  return json{{"type", "waveform"}, {"tracks", std::move(tracks)}}.dump();
}

std::optional<std::string> Studio::mesh_file(std::size_t index) const {
  if (!rig_.kinematics || index >= rig_.kinematics->visuals.size()) return std::nullopt;
  const kinematics::LinkVisual& v = rig_.kinematics->visuals[index];
  std::error_code ignored;
  if (v.shape != kinematics::VisualShape::mesh || !std::filesystem::is_regular_file(v.mesh_path, ignored)) return std::nullopt;
  return v.mesh_path;
}

std::string Studio::hello() const {
  std::string head =
      json{{"type", "hello"}, {"protocol", 1}, {"rig", rig_json(rig_)}, {"vocabulary", curve_vocabulary_json()}}.dump();
  head.pop_back();
  const std::lock_guard lock(mutex_);
  return head + "," + show_fields() + "}";
}

void Studio::play_document() {
  playing_ = std::make_shared<const playback::Show>(document_.show());
  ++version_;
  // The figure follows while the run lasts; without one the document alone changes.
  if (session_) (void)session_->replace_show(playing_);
}

Replies Studio::handle(std::string_view message) {
  const std::string type = request_type(message);
  Replies out;
  const std::lock_guard lock(mutex_);
  try {
    const ClientMessage parsed = parse_client_message(message, channel_names_, target_names_);
    std::visit(
        [&](const auto& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, session::Command>) {
            if (!session_) throw ProtocolError("message '" + type + "': no figure is running");
            if (!session_->command(m))
              throw ProtocolError("message '" + type + "': the figure's command queue is full; send it again");
            out.to_sender = ok_reply(type);
          } else if constexpr (std::is_same_v<M, Estop>) {
            if (session_) session_->estop();
            out.to_sender = ok_reply(type);
          } else if constexpr (std::is_same_v<M, Edit>) {
            if (m.continues) document_.continue_last(m.edits);
            else document_.apply(m.edits);
            play_document();
            out.to_sender = ok_reply(type);
            out.to_all.push_back(change_message());
          } else if constexpr (std::is_same_v<M, Undo> || std::is_same_v<M, Redo>) {
            const bool done = std::is_same_v<M, Undo> ? document_.undo() : document_.redo();
            if (!done) throw ProtocolError("message '" + type + "': there is nothing to " + type);
            play_document();
            out.to_sender = ok_reply(type);
            out.to_all.push_back(change_message());
          } else if constexpr (std::is_same_v<M, Curves>) {
            out.to_sender = curves_message(m.channels);
          } else if constexpr (std::is_same_v<M, Check>) {
            out.to_sender = check_message();
          } else if constexpr (std::is_same_v<M, Waveform>) {
            out.to_sender = waveform_message();
          } else if constexpr (std::is_same_v<M, Retime>) {
            document_.retime(rig_);
            play_document();
            out.to_sender = ok_reply(type);
            out.to_all.push_back(show_message());
          } else {
            static_assert(std::is_same_v<M, Save>);
            if (show_path_.empty())
              throw ProtocolError("message 'save': the show has no file; start the studio with a show path to save to");
            document_.save(show_path_);
            out.to_sender = json{{"type", "saved"}, {"file", show_path_}}.dump();
            out.to_all.push_back(show_message());
          }
        },
        parsed);
  } catch (const ProtocolError& e) {
    out = {error_reply(type, e.what()), {}};
  } catch (const edit::EditError& e) {
    out = {error_reply(type, std::string("message '") + type + "': " + e.what()), {}};
  } catch (const InputError& e) {
    out = {error_reply(type, std::string("message '") + type + "': " + e.what()), {}};
  }
  return out;
}

void Studio::on_tick(const session::TickRecord& record) {
  const std::lock_guard lock(status_mutex_);
  newest_.tick = record.tick;
  newest_.show_time_s = record.show_time_s;
  newest_.paused = record.paused;
  newest_.looping = record.looping;
  newest_.estop = record.estop;
  newest_.stop_requested = record.stop_requested;
  newest_.phase = record.phase;
  newest_.fault = record.fault;
  newest_.channels.assign(record.channels.begin(), record.channels.end());
  newest_.links.assign(record.links.begin(), record.links.end());
  newest_.targets.assign(record.targets.begin(), record.targets.begin() + static_cast<std::ptrdiff_t>(record.target_count));
  for (std::size_t i = 0; i < record.command_count; ++i)
    if (record.commands[i].outcome != session::CommandOutcome::applied && refused_.size() < kMaxRefusedKept)
      refused_.push_back(record.commands[i]);
  fresh_ = true;
}

std::string Studio::status() {
  Snapshot s;
  {
    const std::lock_guard lock(status_mutex_);
    s = newest_;
  }
  return status_json(s);
}

std::vector<std::string> Studio::take_status() {
  Snapshot s;
  std::vector<session::CommandRecord> refused;
  {
    const std::lock_guard lock(status_mutex_);
    if (!fresh_ && refused_.empty()) return {};
    fresh_ = false;
    s = newest_;
    refused.swap(refused_);
  }
  std::vector<std::string> out;
  for (const session::CommandRecord& r : refused) {
    json m = {{"type", "refused"}, {"command", session::to_string(r.command.kind)}, {"outcome", session::to_string(r.outcome)}};
    if (r.command.kind == session::CommandKind::hold || r.command.kind == session::CommandKind::release)
      m["channel"] = r.command.channel < channel_names_.size() ? json(channel_names_[r.command.channel]) : json(nullptr);
    if (r.command.kind == session::CommandKind::aim || r.command.kind == session::CommandKind::unaim)
      m["target"] = r.command.channel;
    out.push_back(m.dump());
  }
  out.push_back(status_json(s));
  return out;
}

std::string Studio::status_json(const Snapshot& s) const {
  json channels = json::array();
  for (std::size_t c = 0; c < s.channels.size(); ++c) {
    const session::ChannelRecord& ch = s.channels[c];
    channels.push_back({{"name", channel_names_[c]},
                        {"target", maybe(ch.target)},
                        {"command", maybe(ch.command)},
                        {"measured", maybe(ch.measured)},
                        {"held", ch.held},
                        {"temperature", maybe(ch.temperature_c)},
                        {"load", maybe(ch.load)},
                        {"device_faults", ch.device_faults}});
  }
  json links = json::array();
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const firmware_iface::LinkCounters& k = s.links[l];
    links.push_back({{"name", l < rig_.links.size() ? rig_.links[l].name : std::string()},
                     {"exchanges", k.exchanges},
                     {"bytes_sent", k.bytes_sent},
                     {"bytes_received", k.bytes_received},
                     {"replies", k.replies},
                     {"crc_errors", k.crc_errors},
                     {"timeouts", k.timeouts},
                     {"retries", k.retries},
                     {"device_errors", k.device_errors},
                     {"reconnects", k.reconnects}});
  }
  json fault = nullptr;
  if (s.fault.cause != control::FaultCause::none)
    fault = {{"cause", control::to_string(s.fault.cause)}, {"index", s.fault.index}, {"value", maybe(s.fault.value)}};
  double duration = 0;
  json targets = json::array();
  {
    const std::lock_guard lock(mutex_);
    duration = playing_->duration;
    for (std::size_t i = 0; i < s.targets.size() && i < playing_->targets.size(); ++i)
      targets.push_back({{"name", playing_->targets[i].effector},
                         {"point", {s.targets[i].point[0], s.targets[i].point[1], s.targets[i].point[2]}},
                         {"held", s.targets[i].held}});
  }
  return json{{"type", "status"},
              {"tick", s.tick},
              {"phase", control::to_string(s.phase)},
              {"show_time", s.show_time_s},
              {"duration", duration},
              {"paused", s.paused},
              {"loop", s.looping},
              {"estop", s.estop},
              {"stopping", s.stop_requested},
              {"fault", fault},
              {"channels", channels},
              {"targets", targets},
              {"links", links}}
      .dump();
}

}  // namespace avar::studio
