// Reads a rig file and a show file and checks the show against the rig, as every front end does
// before anything moves: linked against the readers alone (avar::config_reader), so that its link
// closure shows what reading files costs (see CMakeLists.txt beside it). Prints one line; exits 1
// with the reader's message on bad input.
#include <exception>
#include <iostream>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " RIG.yaml SHOW.yaml\n";
    return 2;
  }
  try {
    const avar::rig::Rig rig = avar::config::load_rig_file(argv[1]);
    const avar::playback::Show show = avar::config::load_show_file(argv[2]);
    const avar::config::ShowCheck check = avar::config::check_show_against_rig(show, rig);
    for (const avar::config::Finding& f : check.errors) std::cerr << f.to_string() << "\n";
    if (!check.ok()) return 1;
    std::cout << "rig '" << rig.name << "': " << rig.links.size() << " links, " << rig.channels.size() << " channels; show '"
              << show.name << "': " << show.tracks.size() << " tracks\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
