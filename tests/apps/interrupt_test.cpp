// Ctrl-C on a real-time `avar play`, as a separate process: the first SIGINT eases the figure to
// rest and exits 130; a second one releases every servo at once.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/temp_file.hpp"

extern char** environ;

namespace avar::app {
namespace {

struct Child {
  pid_t pid = -1;
  int err_fd = -1;
};

Child spawn_play(const std::string& trace) {
  std::vector<std::string> args{AVAR_BINARY,  "play", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml",
                                "--rig",      AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml",
                                "--no-progress", "--trace", trace};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int pipe_fds[2];
  EXPECT_EQ(::pipe(pipe_fds), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  Child child;
  EXPECT_EQ(posix_spawn(&child.pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  child.err_fd = pipe_fds[0];
  return child;
}

/// Reads the child's stderr until `marker` appears (or EOF); returns what was read.
std::string read_until(int fd, const std::string& marker) {
  std::string text;
  char buf[256];
  while (text.find(marker) == std::string::npos) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

int wait_exit(Child& child, std::string& rest_of_stderr) {
  rest_of_stderr = read_until(child.err_fd, "\x01never");
  ::close(child.err_fd);
  int status = 0;
  ::waitpid(child.pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> last_row(const std::string& csv_path) {
  std::ifstream csv(csv_path);
  std::string line, last;
  while (std::getline(csv, line)) last = line;
  std::vector<std::string> cells;
  std::stringstream in(last);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST(Interrupt, FirstCtrlCEasesToRestAndExits130) {
  const std::string trace = testing::temp_path("trace.csv");
  Child child = spawn_play(trace);
  ASSERT_NE(read_until(child.err_fd, "Ctrl-C eases to rest").find("playing"), std::string::npos);
  ::kill(child.pid, SIGINT);
  std::string err;
  EXPECT_EQ(wait_exit(child, err), 130) << err;
  EXPECT_NE(err.find("interrupt: easing to rest"), std::string::npos) << err;
  EXPECT_NE(err.find("stopped: eased to rest after an interrupt"), std::string::npos) << err;
  const auto cells = last_row(trace);
  ASSERT_EQ(cells.size(), 2u + 8u * 3u);
  EXPECT_EQ(cells[1], "finished");
  EXPECT_DOUBLE_EQ(std::stod(cells[3]), 0.0);         // jaw commanded at rest
  EXPECT_DOUBLE_EQ(std::stod(cells[2 + 6 * 3 + 1]), 20.0);  // lid_left at rest
}

TEST(Interrupt, SecondCtrlCReleasesAtOnce) {
  const std::string trace = testing::temp_path("trace.csv");
  Child child = spawn_play(trace);
  read_until(child.err_fd, "Ctrl-C eases to rest");
  ::kill(child.pid, SIGINT);
  // Signals of one kind do not queue: wait until the first was taken before sending the next.
  read_until(child.err_fd, "interrupt again to release");
  ::kill(child.pid, SIGINT);
  std::string err;
  EXPECT_EQ(wait_exit(child, err), 130) << err;
  EXPECT_NE(err.find("released: every actuator was let go at once"), std::string::npos) << err;
}

}  // namespace
}  // namespace avar::app
