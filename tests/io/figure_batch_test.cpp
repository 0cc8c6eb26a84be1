// The figures of an output directory rendered together (io::FigureBatch): every script
// written when added, every SVG whole or absent, a failed figure reported and removed,
// --no-figures honoured, and a batch left unfinished keeping no earlier run's figure.
#include "io/write/figure_batch.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/write/plot.hpp"
#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;
namespace io = pronk::io;

namespace {

/// A fresh directory under /tmp, removed at scope exit.
struct FigureDir : cli_support::TempDir {
  FigureDir() : cli_support::TempDir("figure") {}
};

using cli_support::slurp;

/// A small figure `name` with its data inline (curve k).
std::string figure_script(const std::string& name, int k) {
  return "set terminal svg size 300,200 dynamic enhanced font 'Helvetica,11'\n"
         "set output '" +
         name + ".svg'\n$d << EOD\n0 0\n1 " + std::to_string(k) + "\n2 " + std::to_string(2 * k) +
         "\nEOD\nplot $d w l t 'curve " + std::to_string(k) + "'\n";
}

/// Captures std::cerr while it lives.
struct CerrCapture {
  std::ostringstream text;
  std::streambuf* old = std::cerr.rdbuf(text.rdbuf());
  ~CerrCapture() { std::cerr.rdbuf(old); }
  CerrCapture() = default;
  CerrCapture(const CerrCapture&) = delete;
  CerrCapture& operator=(const CerrCapture&) = delete;
};

/// Rendering switched off (--no-figures) while it lives.
struct NoFigures {
  NoFigures() { io::set_render_figures(false); }
  ~NoFigures() { io::set_render_figures(true); }
  NoFigures(const NoFigures&) = delete;
  NoFigures& operator=(const NoFigures&) = delete;
};

}  // namespace

TEST_CASE("A figure batch writes each script when added and renders every figure", "[io][figure]") {
  if (!io::gnuplot_available()) {
    WARN("skipped: no gnuplot on PATH");
    return;
  }
  FigureDir dir;
  const int n = 7;  // more figures than cores
  std::string alone;
  {
    io::FigureBatch one;
    one.add(dir.path, "alone", figure_script("alone", 3));
    REQUIRE(one.finish());
    alone = slurp(dir.path + "/alone.svg");
  }
  io::FigureBatch figures;
  for (int k = 0; k < n; ++k) {
    const std::string name = "f" + std::to_string(k);
    figures.add(dir.path, name, figure_script(name, k));
    CHECK(slurp(dir.path + "/" + name + ".gp") == figure_script(name, k));
    CHECK_FALSE(fs::exists(dir.path + "/" + name + ".svg"));  // rendered on finish
  }
  CHECK(figures.finish());
  for (int k = 0; k < n; ++k) {
    const std::string svg = slurp(dir.path + "/f" + std::to_string(k) + ".svg");
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK_THAT(svg, Contains("</svg>") && Contains("curve " + std::to_string(k)));
  }
  // The same script renders the same bytes in a batch of one and among others.
  io::FigureBatch again;
  again.add(dir.path, "alone", figure_script("alone", 3));
  for (int k = 0; k < 3; ++k) {
    again.add(dir.path, "g" + std::to_string(k), figure_script("g" + std::to_string(k), k));
  }
  CHECK(again.finish());
  CHECK(slurp(dir.path + "/alone.svg") == alone);
  for (const auto& e : fs::directory_iterator(dir.path)) {
    CHECK(e.path().string().find(".tmp") == std::string::npos);
  }
}

TEST_CASE("A figure gnuplot fails on is reported and removed, the others rendered",
          "[io][figure]") {
  if (!io::gnuplot_available()) {
    WARN("skipped: no gnuplot on PATH");
    return;
  }
  FigureDir dir;
  std::ofstream(dir.path + "/bad.svg") << "an earlier run's figure";
  CerrCapture err;
  io::FigureBatch figures;
  figures.add(dir.path, "good", figure_script("good", 1));
  figures.add(dir.path, "bad",
              "set terminal svg\nset output 'bad.svg'\nplot no_such_function(x)\n");
  CHECK_FALSE(figures.finish());
  CHECK(fs::exists(dir.path + "/good.svg"));
  CHECK_FALSE(fs::exists(dir.path + "/bad.svg"));
  CHECK(fs::exists(dir.path + "/bad.gp"));
  CHECK(err.text.str() == "pronk: gnuplot failed on " + dir.path + "/bad.gp\n");
}

TEST_CASE("A figure script must name its output", "[io][figure]") {
  FigureDir dir;
  io::FigureBatch figures;
  CHECK_THROWS_AS(figures.add(dir.path, "x", "set terminal svg\nplot x\n"), std::logic_error);
  CHECK(fs::exists(dir.path + "/x.gp"));  // the script is written first, as it always was
}

TEST_CASE("Without figures (--no-figures) a batch writes the scripts and renders nothing",
          "[io][figure]") {
  FigureDir dir;
  std::ofstream(dir.path + "/a.svg") << "an earlier run's figure";
  NoFigures off;
  CerrCapture err;
  io::FigureBatch figures;
  figures.add(dir.path, "a", figure_script("a", 1));
  figures.add(dir.path, "b", figure_script("b", 2));
  CHECK_FALSE(figures.finish());
  CHECK(fs::exists(dir.path + "/a.gp"));
  CHECK(fs::exists(dir.path + "/b.gp"));
  CHECK_FALSE(fs::exists(dir.path + "/a.svg"));
  CHECK_FALSE(fs::exists(dir.path + "/b.svg"));
  CHECK(err.text.str().empty());
}

TEST_CASE("A batch left unfinished keeps no earlier run's figure", "[io][figure]") {
  FigureDir dir;
  std::ofstream(dir.path + "/a.svg") << "an earlier run's figure";
  {
    io::FigureBatch figures;
    figures.add(dir.path, "a", figure_script("a", 1));
  }  // e.g. a data file failed to be written after the figure was added
  CHECK(fs::exists(dir.path + "/a.gp"));
  CHECK_FALSE(fs::exists(dir.path + "/a.svg"));
}
