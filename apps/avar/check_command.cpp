#include "avar/check_command.hpp"

#include <cmath>
#include <ostream>

#include "avar/config/feasibility.hpp"
#include "avar/config/input_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

/// " (N of behaviour)" when some layers hold behaviour instead of clips.
std::string behaviour_note(const playback::Show& show) {
  std::size_t n = 0;
  for (const playback::Layer& layer : show.layers) n += layer.behaviour ? 1 : 0;
  return n == 0 ? "" : " (" + std::to_string(n) + " of behaviour)";
}

/// Segments over a limit, or within this share of one, are listed in a summary.
constexpr double kNearLimit = 0.9;

/// A count of the segments and the worst, then each over or near a limit (every one if `every`).
/// Returns how many are over a limit.
std::size_t list_segments(const std::vector<config::SegmentDemand>& segments, bool every, std::ostream& out) {
  std::size_t over = 0, near = 0;
  const config::SegmentDemand* worst = nullptr;
  for (const auto& s : segments) {
    over += s.usage() > 1 + 1e-9 ? 1 : 0;
    near += s.usage() >= kNearLimit && s.usage() <= 1 + 1e-9 ? 1 : 0;
    if (!worst || s.usage() > worst->usage()) worst = &s;
  }
  out << "feasibility: " << segments.size() << " segment(s), " << over << " over a limit, " << near << " within 10 % of one";
  if (worst)
    out << "; the worst, " << worst->channel << " " << format_number(worst->t0) << "-" << format_number(worst->t1) << " s ("
        << to_string(worst->where) << "), uses " << format_number(std::round(worst->usage() * 1000) / 10) << " % of a limit";
  out << (every ? "" : " (--verbose lists every segment)") << '\n';
  for (const auto& s : segments) {
    const double u = s.usage();
    if (every || u >= kNearLimit)
      out << (u > 1 + 1e-9 ? "over: " : u >= kNearLimit ? "near: " : "segment: ") << s.to_string() << '\n';
  }
  return over;
}

}  // namespace

int run_check(const std::string& show_path, const std::string& rig_path, const std::string& retime_path, std::ostream& out,
              std::ostream& err, SegmentListing listing) {
  try {
    const rig::Rig rig = config::load_rig_file(rig_path);
    (void)config::load_input_map(rig, rig_path, false);  // the rig's inputs: section, checked whole too
    playback::Show show = config::load_show_file(show_path);
    const config::ShowCheck check = config::check_show_against_rig(show, rig);
    for (const auto& w : check.warnings) err << "warning: " << w.to_string() << '\n';
    for (const auto& e : check.errors) err << "error: " << e.to_string() << '\n';
    if (!check.ok()) {
      err << check.errors.size() << " error(s): the show cannot play on this rig\n";
      return kExitBadInput;
    }
    config::bind_show_behaviour(show, rig);
    std::size_t keys = 0;
    for (const auto& t : show.tracks) keys += t.raw.keys.size();
    out << "ok: show '" << show.name << "' (" << show.duration << " s, " << show.tracks.size() << " tracks, " << keys << " keys"
        << (show.targets.empty() ? "" : ", " + std::to_string(show.targets.size()) + " IK targets")
        << (show.layered() ? ", " + std::to_string(show.clips.size()) + " clips on " + std::to_string(show.layers.size()) +
                                 " layers" + behaviour_note(show)
                           : "")
        << (show.loop ? ", looping" : "") << ") fits rig '" << rig.name << "' (" << rig.channels.size() << " channels, "
        << rig.actuators.size() << " actuators, " << rig.links.size() << " link(s))";
    if (!check.warnings.empty()) out << " with " << check.warnings.size() << " warning(s)";
    out << '\n';
    const std::vector<config::Infeasible> infeasible = config::check_feasibility(show, rig);
    const bool by_segment = listing != SegmentListing::infeasible && !show.layered();
    const std::size_t segments_over =
        by_segment ? list_segments(config::segment_demands(show, rig), listing == SegmentListing::every, out) : 0;
    std::size_t jumps = 0;
    for (const auto& f : infeasible) {
      const bool jump = f.kind == config::Infeasible::Kind::jump;
      jumps += jump ? 1 : 0;
      if (jump || !by_segment) out << (jump ? "step: " : "infeasible: ") << f.to_string() << '\n';
    }
    out << (by_segment ? segments_over : infeasible.size() - jumps)
        << " segment(s) ask more speed, acceleration or range than the rig allows"
        << (infeasible.size() > jumps ? "; the limiter will slow or clamp them, --retime writes a show that does not" : "")
        << "; " << jumps << " step jump(s), shaped by the limiter\n";
    if (!retime_path.empty()) {
      const playback::Show retimed = config::retime(show, rig);
      config::write_show_file(retime_path, retimed, "written by avar check --retime");
      out << "retimed show: " << retime_path << " (" << retimed.duration << " s, was " << show.duration << " s)\n";
    }
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
