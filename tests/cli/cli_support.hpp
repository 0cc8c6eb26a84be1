// Shared helpers of the end-to-end CLI tests: a self-removing temporary
// directory, shell quoting, whole-file reads and writes, and running the built
// `pronk` (PRONK_EXE) in a directory with stdout and stderr captured.
#pragma once

#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace cli_support {

/// A fresh directory under /tmp, removed with everything in it on destruction.
class TempDir {
 public:
  /// `tag` names the test file in the directory's name (pronk_<tag>_test_XXXXXX).
  explicit TempDir(const std::string& tag) {
    std::string tmpl = "/tmp/pronk_" + tag + "_test_XXXXXX";
    const char* p = ::mkdtemp(tmpl.data());
    REQUIRE(p != nullptr);
    path = p;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return path + "/" + name; }

  std::string path;
};

/// `s` single-quoted for /bin/sh.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// The whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

inline void write_file(const std::string& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
}

struct Run {
  int code = -1;  ///< exit code; -1 when killed by a signal
  std::string out, err;
};

/// Runs pronk with `args` (each one shell-quoted) in `dir`, capturing stdout and stderr.
inline Run pronk(const TempDir& dir, const std::vector<std::string>& args) {
  // Built with += only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string cmd = "cd ";
  cmd += quote(dir.path);
  cmd += " && exec ";
  cmd += quote(PRONK_EXE);
  for (const auto& a : args) {
    cmd += ' ';
    cmd += quote(a);
  }
  cmd += " >";
  cmd += quote(dir / ".stdout");
  cmd += " 2>";
  cmd += quote(dir / ".stderr");
  cmd += " </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.out = slurp(dir / ".stdout");
  r.err = slurp(dir / ".stderr");
  return r;
}

/// Bad input: exit 2 and exactly one line, "pronk: error: " followed by `starts`.
inline void check_bad_input(const Run& r, const std::string& starts) {
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Matchers::StartsWith("pronk: error: " + starts));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

}  // namespace cli_support
