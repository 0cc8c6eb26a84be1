#include "optimize/output_lock.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/load/input_error.hpp"

namespace pronk::optimize {

namespace {

// What the holder wrote into the lock file ("pid 1234 (pronk optimize)"), "" when nothing.
std::string holder_of(int fd) {
  char buf[256] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string s(buf, n > 0 ? static_cast<size_t>(n) : 0);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// Whether `fd` is the file at `path` now (the holder before us may have removed it).
bool same_file(int fd, const std::string& path) {
  struct stat a {};
  struct stat b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

// NAME.tmp.PID with no process PID alive: a temporary a killed io::write_file_atomic left.
bool is_stale_temporary(const std::string& name) {
  const size_t at = name.rfind(".tmp.");
  if (at == std::string::npos || at == 0 || at + 5 == name.size() || at + 5 + 9 < name.size() ||
      name.find_first_not_of("0123456789", at + 5) != std::string::npos)
    return false;
  const pid_t pid = static_cast<pid_t>(std::stol(name.substr(at + 5)));
  return pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH;
}

}  // namespace

OutputLock::OutputLock(const std::string& dir, const std::string& what)
    : path_(dir + "/pronk.lock") {
  // A few attempts: each one fails only when the holder removed the file we opened.
  for (int attempt = 0; attempt < 100; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot create " + path_ + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string holder = holder_of(fd_);
      ::close(fd_);
      fd_ = -1;
      if (err != EWOULDBLOCK)
        throw std::runtime_error("cannot lock " + path_ + ": " + std::strerror(err));
      throw io::InputError(
          path_, "",
          "an output directory no other run is writing to (wait until it ends, or choose "
          "another --out)",
          (holder.empty() ? std::string("another process") : holder) + " holding its lock");
    }
    if (same_file(fd_, path_)) {
      const std::string text = "pid " + std::to_string(::getpid()) + " (" + what + ")\n";
      if (::ftruncate(fd_, 0) != 0 ||
          ::pwrite(fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
        const std::string err = std::strerror(errno);
        ::close(fd_);
        throw std::runtime_error("cannot write " + path_ + ": " + err);
      }
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  throw std::runtime_error("cannot lock " + path_ + ": the lock file keeps being replaced");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still holding it: see same_file()
  ::close(fd_);
}

long remove_stale_temporaries(const std::string& dir, int depth) {
  namespace fs = std::filesystem;
  std::error_code ec;
  long removed = 0;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it.depth() >= depth) it.disable_recursion_pending();
    if (it->is_regular_file(ec) && is_stale_temporary(it->path().filename().string()) &&
        fs::remove(it->path(), ec))
      ++removed;
  }
  return removed;
}

}  // namespace pronk::optimize
