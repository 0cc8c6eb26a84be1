#include "io/write/plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "io/write/atomic_file.hpp"

extern char** environ;

namespace pronk::io {

namespace {
std::once_flag g_missing_reported;
std::atomic<bool> g_render{true};

// Closes a file descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("cannot render a figure: " + what + ": " + std::strerror(errno));
}

// The script held in memory (an anonymous file), to be gnuplot's standard input.
int script_input(const std::string& script) {
  const int fd = ::memfd_create("pronk-figure.gp", MFD_CLOEXEC);
  if (fd < 0) fail("memfd_create");
  for (size_t done = 0; done < script.size();) {
    const ssize_t n = ::write(fd, script.data() + done, script.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      fail("write");
    }
    done += static_cast<size_t>(n);
  }
  if (::lseek(fd, 0, SEEK_SET) != 0) {
    ::close(fd);
    fail("lseek");
  }
  return fd;
}

// Everything readable from `fd` until end of file.
std::string read_all(int fd) {
  std::string out;
  char buf[65536];
  while (true) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return out;
    out.append(buf, static_cast<size_t>(n));
  }
}

// True when `svg` is a whole SVG document (gnuplot ended it).
bool plot_whole_svg(const std::string& svg) {
  const size_t end = svg.find_last_not_of(" \t\r\n");
  return end != std::string::npos && end >= 11 && svg.compare(0, 5, "<?xml") == 0 &&
         svg.compare(end - 5, 6, "</svg>") == 0;
}

// Runs gnuplot in `dir` on `script` (which sends its figure to standard output) and returns
// what it wrote; nothing when gnuplot fails or its output is not a whole SVG document.
// Every descriptor is opened close-on-exec, so concurrent runs do not hold each other's pipes.
std::optional<std::string> run_gnuplot(const std::string& dir, const std::string& script) {
  Fd in{script_input(script)};
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) fail("pipe");
  Fd out_read{pipe_fds[0]}, out_write{pipe_fds[1]};
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_adddup2(&actions, in.fd, 0);
  ::posix_spawn_file_actions_adddup2(&actions, out_write.fd, 1);
  ::posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  ::posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  ::posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return std::nullopt;
  ::close(out_write.fd);
  out_write.fd = -1;
  std::string svg = read_all(out_read.fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !plot_whole_svg(svg)) return std::nullopt;
  return svg;
}

// True when `path` names an executable regular file.
bool plot_executable_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

void set_render_figures(bool render) { g_render = render; }

bool render_figures() { return g_render; }

bool gnuplot_available() {
  // The search posix_spawnp makes: each directory of PATH (empty: the current one), or
  // glibc's default path when PATH is unset.
  static const bool available = [] {
    const char* env = std::getenv("PATH");
    const std::string path = env != nullptr ? env : "/bin:/usr/bin";
    for (size_t begin = 0;;) {
      const size_t end = std::min(path.find(':', begin), path.size());
      const std::string dir = path.substr(begin, end - begin);
      if (plot_executable_file((dir.empty() ? "." : dir) + "/gnuplot")) return true;
      if (end == path.size()) return false;
      begin = end + 1;
    }
  }();
  return available;
}

void report_missing_gnuplot() {
  std::call_once(g_missing_reported, [] {
    std::cerr << "pronk: gnuplot not found: figures not rendered (the .gp scripts and CSV "
                 "data are written; install gnuplot-nox to render them)\n";
  });
}

std::string script_to_stdout(const std::string& name, const std::string& script) {
  // gnuplot writes to standard output and pronk writes the file (atomically), so a figure is
  // whole or absent, even on a full disk; the .gp script keeps its own output file.
  const std::string output = "set output '" + name + ".svg'";
  std::string to_stdout = script;
  const size_t at = to_stdout.find(output);
  if (at == std::string::npos) {
    throw std::logic_error("figure: the script of " + name + " does not " + output);
  }
  to_stdout.replace(at, output.size(), "set output");
  return to_stdout;
}

bool render_svg(const std::string& dir, const std::string& name, const std::string& stdout_script) {
  const std::string svg_path = dir + "/" + name + ".svg";
  const std::optional<std::string> svg = run_gnuplot(dir, stdout_script);
  if (!svg) {
    std::remove(svg_path.c_str());  // no figure rather than one of an earlier run
    return false;
  }
  write_file_atomic(svg_path, *svg);
  return true;
}

}  // namespace pronk::io
