#include "io/write/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/load/input_error.hpp"
#include "io/write/crash_point.hpp"

namespace pronk::io {

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + tmp + ": " + std::strerror(errno));
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string err = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error("cannot write " + tmp + ": " + err);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot flush " + tmp + ": " + std::strerror(errno));
  }
  crash_point();  // tests: a kill that leaves the temporary behind (io/write/crash_point.hpp)
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + err);
  }
}

namespace {

// `text` in double quotes, followed by `rest` (built with += only: GCC 12 warns falsely
// on "literal" + std::string&&).
std::string quoted(const std::string& text, const char* rest) {
  std::string out = "\"";
  out += text;
  out += "\"";
  out += rest;
  return out;
}

// True when a failure to create a directory entry (errno `err`) is the location's fault:
// a bad input. A full disk, a quota or an I/O error is a failure of the run instead.
bool location_error(int err) {
  return err == EACCES || err == EPERM || err == EROFS || err == ENOENT || err == ENOTDIR ||
         err == ENAMETOOLONG || err == ELOOP || err == EEXIST;
}

// Why no directory can be made in the existing directory `dir` ("" when one can): made and
// removed at once, since permissions do not tell (root passes access(2) on /proc and /sys).
std::string probe_problem(const std::filesystem::path& dir) {
  const std::filesystem::path probe = dir / (".pronk-probe-" + std::to_string(::getpid()));
  if (::mkdir(probe.c_str(), 0700) == 0) {
    ::rmdir(probe.c_str());
    return "";
  }
  const int err = errno;
  if (!location_error(err)) return "";  // e.g. a full disk: the run reports it (exit 1)
  return quoted(dir.string(), ", a directory in which nothing can be created (") +
         std::strerror(err) + ")";
}

// Why `path` cannot be an output directory ("" when it can): the nearest existing part of
// it must be a directory in which pronk can create entries.
std::string output_directory_problem(const std::string& path) {
  if (path.empty()) return "an empty path";
  std::filesystem::path p(path);
  std::error_code ec;
  while (!p.empty() && !std::filesystem::exists(p, ec)) p = p.parent_path();
  if (p.empty()) p = ".";
  if (!std::filesystem::is_directory(p, ec)) {
    return p.string() == path ? quoted(path, ", which exists and is not a directory")
                              : quoted(p.string(), ", a part of the path that is a file");
  }
  if (::access(p.c_str(), W_OK | X_OK) != 0) {
    return quoted(p.string(), ", a directory that is not writable");
  }
  return probe_problem(p);
}

}  // namespace

void check_output_directory(const std::string& path, const std::string& origin) {
  const std::string problem = output_directory_problem(path);
  if (!problem.empty()) {
    throw InputError(origin, "", "a directory that exists or can be created", problem);
  }
}

void make_directories(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (!ec) return;
  if (location_error(ec.value())) {
    std::string problem = output_directory_problem(path);
    if (problem.empty()) problem = quoted(path, ", which cannot be created (") + ec.message() + ")";
    throw InputError(path, "", "a directory that exists or can be created", problem);
  }
  throw std::runtime_error("cannot create directory " + path + ": " + ec.message());
}

}  // namespace pronk::io
