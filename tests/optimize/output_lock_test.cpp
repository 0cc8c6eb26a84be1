// One writer per output directory: a second lock (another process, or this one again) is
// bad input naming the holder's pid; the kernel drops a dead holder's lock; a released
// lock leaves no file. Stale temporaries of write_file_atomic are removed, nothing else.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "optimize/output_lock.hpp"
#include "io/load/input_error.hpp"

namespace fs = std::filesystem;
using pronk::optimize::OutputLock;
using pronk::optimize::remove_stale_temporaries;

namespace {

struct TempDir {
  TempDir() {
    std::string t = (fs::temp_directory_path() / "pronk_lock_XXXXXX").string();
    REQUIRE(::mkdtemp(t.data()) != nullptr);
    path = t;
  }
  ~TempDir() { fs::remove_all(path); }
  std::string path;
};

// The message of the InputError that taking the lock of `dir` throws ("" when none).
std::string refusal(const std::string& dir) {
  try {
    const OutputLock again(dir, "second");
  } catch (const pronk::io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("an output directory has one writer; the second is told the holder's pid",
          "[optimize][lock]") {
  TempDir d;
  {
    const OutputLock lock(d.path, "pronk optimize");
    CHECK(fs::exists(d.path + "/pronk.lock"));
    const std::string msg = refusal(d.path);
    CHECK(msg == d.path +
                     "/pronk.lock: /: expected an output directory no other run is writing to "
                     "(wait until it ends, or choose another --out), found pid " +
                     std::to_string(::getpid()) + " (pronk optimize) holding its lock");
  }
  CHECK_FALSE(fs::exists(d.path + "/pronk.lock"));  // released and removed
  CHECK(refusal(d.path).empty());

  // Another process holds it (a child that locks and waits on a pipe), then dies.
  int to_child[2], to_parent[2];
  REQUIRE(::pipe(to_child) == 0);
  REQUIRE(::pipe(to_parent) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const OutputLock lock(d.path, "child");
    char c = 'x';
    (void)::write(to_parent[1], &c, 1);
    (void)::read(to_child[0], &c, 1);
    ::_exit(0);  // no destructor: as if killed, the lock file stays
  }
  char c = 0;
  REQUIRE(::read(to_parent[0], &c, 1) == 1);
  CHECK_THAT(refusal(d.path), Catch::Matchers::EndsWith("found pid " + std::to_string(pid) +
                                                        " (child) holding its lock"));
  REQUIRE(::write(to_child[1], &c, 1) == 1);
  int status = 0;
  ::waitpid(pid, &status, 0);
  CHECK(fs::exists(d.path + "/pronk.lock"));  // a stale file, but no lock on it
  CHECK(refusal(d.path).empty());
  for (int fd : {to_child[0], to_child[1], to_parent[0], to_parent[1]}) ::close(fd);
}

TEST_CASE("stale temporaries are removed down to the given depth, nothing else",
          "[optimize][lock]") {
  TempDir d;
  // A pid that is certainly gone: a child that has ended and been reaped.
  const pid_t dead = ::fork();
  REQUIRE(dead >= 0);
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string gone = std::to_string(dead), alive = std::to_string(::getpid());
  fs::create_directories(d.path + "/initial/deeper");
  const std::vector<std::string> made = {"summary.md.tmp." + gone,
                                         "initial/trajectory.csv.tmp." + gone,
                                         "initial/deeper/x.tmp." + gone,
                                         "live.tmp." + alive,
                                         "keep.tmp",
                                         "keep.tmp.12a",
                                         ".tmp." + gone,
                                         "design.json"};
  for (const std::string& f : made) std::ofstream(d.path + "/" + f) << "x";
  CHECK(remove_stale_temporaries(d.path, 1) == 2);  // the first two
  for (size_t i = 0; i < made.size(); ++i) CHECK(fs::exists(d.path + "/" + made[i]) == (i >= 2));
  CHECK(remove_stale_temporaries(d.path, 2) == 1);
}
