#include "avar/studio/studio_run.hpp"

#include "avar/config/rig_file.hpp"

#include <charconv>
#include <filesystem>
#include <stdexcept>

namespace avar::studio {

playback::Show new_show(const std::string& name, double duration_s) {
  playback::Show show = session::live_only_show(duration_s);
  show.name = name;
  return show;
}

StudioFiles open_studio_files(const std::string& rig_path, const std::optional<std::string>& show_path,
                              const std::optional<std::string>& inputs_path) {
  rig::Rig rig = config::load_rig_file(rig_path);
  config::InputMap inputs =
      inputs_path ? config::load_input_map(rig, *inputs_path, true) : config::load_input_map(rig, rig_path, false);
  const bool new_file = show_path && !std::filesystem::exists(*show_path);
  edit::ShowDocument document = !show_path ? edit::ShowDocument(new_show("untitled"))
                                : new_file ? edit::ShowDocument(new_show(std::filesystem::path(*show_path).stem().string()))
                                           : edit::ShowDocument::open(*show_path);
  config::ShowCheck check = config::check_show_against_rig(document.show(), rig);
  // A new show drives no channel yet: that it holds the rest pose is no news.
  if (!show_path || new_file) check.warnings.clear();
  return {std::move(rig), std::move(inputs), std::move(document), std::move(check), new_file};
}

std::string built_page_dir() {
#ifdef AVAR_STUDIO_PAGE_DIR
  std::string dir = AVAR_STUDIO_PAGE_DIR;
  std::error_code ignored;
  if (std::filesystem::is_regular_file(std::filesystem::path(dir) / "index.html", ignored)) return dir;
#endif
  return {};
}

void parse_listen_address(const std::string& text, ServerOptions& options) {
  const std::size_t colon = text.rfind(':');
  const auto refuse = [&] {
    throw std::invalid_argument("--listen '" + text +
                                "': expected HOST:PORT, such as 127.0.0.1:8080, 0.0.0.0:0 or [::1]:9000 (port 0: any free port)");
  };
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) refuse();
  std::string host = text.substr(0, colon);
  if (host.front() == '[') {
    if (host.back() != ']' || host.size() < 3) refuse();
    host = host.substr(1, host.size() - 2);
  }
  int port = -1;
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(first, last, port);
  if (ec != std::errc() || end != last || port < 0 || port > 65535) refuse();
  options.host = host;
  options.port = port;
}

namespace {

session::FigureRunSetup editor_run(session::FigureRunSetup run) {
  run.session.start_paused = true;
  run.session.hold_at_end = true;
  run.session.stepped = false;
  return run;
}

}  // namespace

StudioRun::StudioRun(const rig::Rig& rig, const config::InputMap& map, edit::ShowDocument document, std::string show_path,
                     StudioSetup setup)
    : studio_(rig, std::move(document), std::move(show_path)), setup_(std::move(setup)) {
  setup_.run = editor_run(std::move(setup_.run));
  figure_ = std::make_unique<session::FigureRun>(rig, studio_.initial_show(), map, setup_.run);
  figure_->session().add_observer(studio_);
  studio_.attach(&figure_->session());
}

StudioRun::~StudioRun() {
  server_.reset();
  studio_.attach(nullptr);
}

std::optional<session::LinkProblem> StudioRun::start() {
  figure_->watch_inputs();
  if (auto problem = figure_->start()) return problem;
  server_.emplace(studio_, setup_.server);
  return std::nullopt;
}

std::string StudioRun::url() const { return server_ ? server_->url() : std::string(); }

control::RunResult StudioRun::run(const std::atomic<int>& interrupts, const std::atomic<bool>* keyboard_estop) {
  control::RunResult result = figure_->run(interrupts, keyboard_estop);
  studio_.attach(nullptr);
  return result;
}

}  // namespace avar::studio
