#pragma once
// `avar studio` as one library object: the show being edited, the figure's run playing it (an
// editor's session: paused at the first frame, holding the end instead of ending), the studio
// that answers the protocol, and the server that carries it.
//
//   StudioRun studio(rig, inputs, std::move(document), "show.yaml", setup);  // nothing moves yet
//   if (auto problem = studio.start()) ...   // the links; homing; then the server listens
//   std::cout << studio.url();
//   studio.run(interrupts, &keyboard_estop); // until stop, Ctrl-C or a fault
//
// Threads: construct, start and run on one thread; the server's threads answer clients.

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "avar/config/input_map.hpp"
#include "avar/config/show_check.hpp"
#include "avar/edit/show_document.hpp"
#include "avar/rig/rig.hpp"
#include "avar/session/figure_run.hpp"
#include "avar/studio/server.hpp"
#include "avar/studio/studio.hpp"

namespace avar::studio {

struct StudioSetup {
  /// The run: links (simulated or a port), rate, scheduling, live inputs, idle life. Its session
  /// is made an editor's: start_paused and hold_at_end are set, and the clock is never stepped.
  session::FigureRunSetup run;
  ServerOptions server;
};

/// A show for a file that does not exist yet: no tracks, `duration_s` long, named `name`.
playback::Show new_show(const std::string& name, double duration_s = 10.0);

/// What `avar studio` opens before anything moves: the rig, its inputs map, the show to edit and
/// the show checked against the rig (check.ok() false: it must not run; a new show has no
/// warnings, though it drives no channel yet).
struct StudioFiles {
  rig::Rig rig;
  config::InputMap inputs;
  edit::ShowDocument document;
  config::ShowCheck check;
  bool new_file = false;  ///< show_path does not exist yet: a new show, written there on save
};

/// Opens the rig, its live controls' mappings (`inputs_path`'s inputs: section, or the rig's own)
/// and the show: the show file when it exists, a new show named after it when it does not, a new
/// "untitled" show without a path. InputError (file:line:col) for a file that cannot be read.
StudioFiles open_studio_files(const std::string& rig_path, const std::optional<std::string>& show_path,
                              const std::optional<std::string>& inputs_path = std::nullopt);

/// The folder of the browser page built with this avar (index.html and what it loads); empty when
/// this build made none (it needs node, npm and emscripten) or the folder is gone.
std::string built_page_dir();

/// "HOST:PORT" ("127.0.0.1:8080", "0.0.0.0:0", "[::1]:9000") into the server's host and port;
/// std::invalid_argument naming what was expected.
void parse_listen_address(const std::string& text, ServerOptions& options);

class StudioRun {
 public:
  /// `document` must be validated against `rig` (config::check_show_against_rig); it is saved to
  /// `show_path` (empty: save is refused). `rig` and `map` are borrowed. Opens the run as
  /// session::FigureRun does (its errors), nothing moving yet.
  StudioRun(const rig::Rig& rig, const config::InputMap& map, edit::ShowDocument document, std::string show_path,
            StudioSetup setup);
  ~StudioRun();
  StudioRun(const StudioRun&) = delete;
  StudioRun& operator=(const StudioRun&) = delete;

  /// Starts the links and homes the figure to the show's first frame, then listens (the
  /// server's std::runtime_error when it cannot). The first link that did not start is
  /// returned, nothing moved and nothing listening.
  std::optional<session::LinkProblem> start();
  /// The page's address (after start()).
  std::string url() const;
  /// Serves until a client's stop, Ctrl-C (`interrupts`), or a fault; `keyboard_estop` as
  /// FigureRun::run. The server stops taking messages when the run ends.
  control::RunResult run(const std::atomic<int>& interrupts, const std::atomic<bool>* keyboard_estop);

  const Studio& studio() const noexcept { return studio_; }
  const session::FigureRun& figure() const noexcept { return *figure_; }
  const Server* server() const noexcept { return server_ ? &*server_ : nullptr; }

 private:
  Studio studio_;
  StudioSetup setup_;
  std::unique_ptr<session::FigureRun> figure_;
  std::optional<Server> server_;
};

}  // namespace avar::studio
