#include "avar/check_command.hpp"

#include <ostream>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {

int run_check(const std::string& show_path, const std::string& rig_path, std::ostream& out, std::ostream& err) {
  try {
    const control::Rig rig = config::load_rig_file(rig_path);
    const playback::Show show = config::load_show_file(show_path);
    const config::ShowCheck check = config::check_show_against_rig(show, rig);
    for (const auto& w : check.warnings) err << "warning: " << w.to_string() << '\n';
    for (const auto& e : check.errors) err << "error: " << e.to_string() << '\n';
    if (!check.ok()) {
      err << check.errors.size() << " error(s): the show cannot play on this rig\n";
      return kExitBadInput;
    }
    std::size_t keys = 0;
    for (const auto& t : show.tracks) keys += t.raw.keys.size();
    out << "ok: show '" << show.name << "' (" << show.duration << " s, " << show.tracks.size() << " tracks, " << keys
        << " keys" << (show.loop ? ", looping" : "") << ") fits rig '" << rig.name << "' (" << rig.channels.size()
        << " channels, " << rig.actuators.size() << " actuators, " << rig.links.size() << " link(s))";
    if (!check.warnings.empty()) out << " with " << check.warnings.size() << " warning(s)";
    out << '\n';
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
