#include "avar/check_command.hpp"

#include <ostream>

#include "avar/config/feasibility.hpp"
#include "avar/config/input_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

/// " (N of behaviour)" when some layers hold behaviour instead of clips.
std::string behaviour_note(const playback::Show& show) {
  std::size_t n = 0;
  for (const playback::Layer& layer : show.layers) n += layer.behaviour ? 1 : 0;
  return n == 0 ? "" : " (" + std::to_string(n) + " of behaviour)";
}

}  // namespace

int run_check(const std::string& show_path, const std::string& rig_path, const std::string& retime_path, std::ostream& out,
              std::ostream& err) {
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
    out << "ok: show '" << show.name << "' (" << show.duration << " s, " << show.tracks.size() << " tracks, " << keys
        << " keys" << (show.targets.empty() ? "" : ", " + std::to_string(show.targets.size()) + " IK targets") << (show.layered() ? ", " + std::to_string(show.clips.size()) + " clips on " + std::to_string(show.layers.size()) + " layers" + behaviour_note(show) : "") << (show.loop ? ", looping" : "") << ") fits rig '" << rig.name << "' (" << rig.channels.size()
        << " channels, " << rig.actuators.size() << " actuators, " << rig.links.size() << " link(s))";
    if (!check.warnings.empty()) out << " with " << check.warnings.size() << " warning(s)";
    out << '\n';
    const std::vector<config::Infeasible> infeasible = config::check_feasibility(show, rig);
    std::size_t jumps = 0;
    for (const auto& f : infeasible) {
      const bool jump = f.kind == config::Infeasible::Kind::jump;
      jumps += jump ? 1 : 0;
      out << (jump ? "step: " : "infeasible: ") << f.to_string() << '\n';
    }
    out << infeasible.size() - jumps << " segment(s) ask more speed, acceleration or range than the rig allows"
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
