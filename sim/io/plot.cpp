#include "sim/io/plot.hpp"

#include <cstdlib>
#include <iostream>
#include <mutex>

#include "sim/io/atomic_file.hpp"

namespace pronk::io {

namespace {
std::once_flag g_missing_reported;

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}
}  // namespace

bool gnuplot_available() {
  static const bool available = std::system("command -v gnuplot >/dev/null 2>&1") == 0;
  return available;
}

bool render_figure(const std::string& dir, const std::string& name, const std::string& script) {
  write_file_atomic(dir + "/" + name + ".gp", script);
  if (!gnuplot_available()) {
    std::call_once(g_missing_reported, [] {
      std::cerr << "pronk: gnuplot not found: figures not rendered (the .gp scripts and CSV "
                   "data are written; install gnuplot-nox to render them)\n";
    });
    return false;
  }
  const std::string cmd =
      "cd " + shell_quote(dir) + " && gnuplot " + shell_quote(name + ".gp") + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "pronk: gnuplot failed on " << dir << "/" << name << ".gp\n";
    return false;
  }
  return true;
}

}  // namespace pronk::io
