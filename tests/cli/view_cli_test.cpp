// End-to-end tests of the pages: `pronk simulate` writes view.html beside its CSVs (or one
// line saying how to get pages when the templates are absent), `pronk view DIR` writes the
// page of a run on disk, refuses (exit 2, nothing written) a directory that is not a run
// or a run with a missing or damaged CSV, and a 100 s run's page stays under 5 MB. A stub
// template ("<p>@PRONK_DATA@</p>") stands in for web/dist; the browser test
// (web/test/pages.mjs) renders the real ones.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kViewScene =
    std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case3_legged_pulse.json";

// Stub templates in `dir`/web, made the page templates of every pronk run from here.
void viewcli_stub_templates(const TempDir& dir) {
  fs::create_directories(dir / "web");
  write_file(dir / "web/view.html", "<p>@PRONK_DATA@</p>");
  write_file(dir / "web/report.html", "<p>@PRONK_DATA@</p>");
  ::setenv("PRONK_WEB_DIR", (dir / "web").c_str(), 1);
}

nlohmann::json viewcli_page_json(const std::string& path) {
  const std::string html = slurp(path);
  REQUIRE(html.size() > 7);
  return nlohmann::json::parse(html.substr(3, html.size() - 7));
}

}  // namespace

TEST_CASE("pronk simulate writes view.html from the run's files", "[cli][page]") {
  TempDir dir("view");
  viewcli_stub_templates(dir);
  const Run r = pronk(dir, {"simulate", kViewScene, "--out", "run"});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("page: run/view.html"));
  const nlohmann::json d = viewcli_page_json(dir / "run/view.html");
  CHECK(d["kind"] == "robot");
  CHECK(d["scene"]["name"] == "case3_legged_pulse");
  // Every sample of trajectory.csv (10 s at 0.01 s fits the budget), same numbers to 6 digits.
  const std::string csv = slurp(dir / "run/trajectory.csv");
  const long rows = static_cast<long>(std::count(csv.begin(), csv.end(), '\n')) - 1;
  CHECK(d["trajectory"]["rows"] == rows);
  CHECK(static_cast<long>(d["trajectory"]["data"][0].size()) == rows);
  CHECK(d["strides"]["columns"][1] == "t_touchdown");

  // `pronk view` on the same directory writes the same page again.
  const std::string first = slurp(dir / "run/view.html");
  fs::remove(dir / "run/view.html");
  const Run v = pronk(dir, {"view", "run"});
  REQUIRE(v.code == 0);
  CHECK(slurp(dir / "run/view.html") == first);

  // A run that falls before its first touchdown (strides.csv without rows) gets its page too.
  const Run fell = pronk(
      dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case1_body_only.json",
            "--set", "/simulation/duration=1", "--set", "/initial/angular_velocity=[40,0,0]",
            "--out", "fell", "-q"});
  CHECK(fell.code == 1);
  const nlohmann::json fd = viewcli_page_json(dir / "fell/view.html");
  CHECK(fd["summary"]["status"] == "fell");
  CHECK(fd["strides"]["rows"] == 0);

  // A mechanism run gets its page too.
  const Run m =
      pronk(dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/pendulum.json",
                  "--out", "mech", "-q"});
  REQUIRE(m.code == 0);
  const nlohmann::json md = viewcli_page_json(dir / "mech/view.html");
  CHECK(md["kind"] == "mechanism");
  CHECK(md["nodes"]["columns"][0] == "t");
}

TEST_CASE("Without page templates a run still writes every file and says how to get pages",
          "[cli][page]") {
  TempDir dir("view");
  ::setenv("PRONK_WEB_DIR", (dir / "absent").c_str(), 1);
  const Run r = pronk(dir, {"simulate", kViewScene, "--out", "run"});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("page: no page templates") && Contains("PRONK_WITH_WEB=1"));
  CHECK(fs::exists(dir / "run/trajectory.csv"));
  CHECK(fs::exists(dir / "run/summary.json"));
  CHECK_FALSE(fs::exists(dir / "run/view.html"));
  const Run v = pronk(dir, {"view", "run"});
  CHECK(v.code == 1);
  CHECK_THAT(v.err, Contains("no page templates"));
}

TEST_CASE("pronk view refuses what is not a run, and damaged runs, writing nothing",
          "[cli][page]") {
  TempDir dir("view");
  viewcli_stub_templates(dir);
  fs::create_directories(dir / "empty");
  Run r = pronk(dir, {"view", "empty"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("empty: /: expected a run, study, map or comparison directory"));
  r = pronk(dir, {"view", "nowhere"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("no such directory"));

  REQUIRE(pronk(dir, {"simulate", kViewScene, "--out", "run", "-q"}).code == 0);
  fs::remove(dir / "run/view.html");
  const std::string good = slurp(dir / "run/trajectory.csv");
  SECTION("a corrupted field") {
    std::string bad = good;
    bad[bad.find('\n', bad.size() / 2) + 1] = 'x';
    write_file(dir / "run/trajectory.csv", bad);
    r = pronk(dir, {"view", "run"});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("trajectory.csv: line") && Contains("expected a finite number"));
  }
  SECTION("a truncated row") {
    write_file(dir / "run/trajectory.csv", good.substr(0, good.size() / 2));
    r = pronk(dir, {"view", "run"});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("trajectory.csv: line") && Contains("fields as in the header"));
  }
  SECTION("a missing CSV") {
    fs::remove(dir / "run/strides.csv");
    r = pronk(dir, {"view", "run"});
    CHECK(r.code == 2);
    CHECK_THAT(
        r.err,
        Contains("strides.csv: /: expected a CSV file written by pronk, found no such file"));
  }
  SECTION("a scene that is not JSON") {
    write_file(dir / "run/scene.resolved.json", "{\"name\": ");
    r = pronk(dir, {"view", "run"});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("scene.resolved.json"));
  }
  CHECK_FALSE(fs::exists(dir / "run/view.html"));
  // Nothing half-written either: no temporary file left behind.
  for (const auto& e : fs::directory_iterator(dir.path + "/run")) {
    CHECK(e.path().filename().string().find("view.html") == std::string::npos);
  }
}

TEST_CASE("The page of a 100 s run stays under 5 MB", "[cli][page]") {
  TempDir dir("view");
  viewcli_stub_templates(dir);
  const Run r = pronk(
      dir, {"simulate", kViewScene, "--out", "run", "-q", "--set", "/simulation/duration=100"});
  REQUIRE(r.code == 0);
  // The stub stands in for a template of 0.85 MB (three.js, uPlot and the page script:
  // web/dist/view.html is 0.83 MB); the data must leave the whole page under 5 MB.
  const auto data = static_cast<double>(fs::file_size(dir / "run/view.html"));
  INFO("data " << data / 1e6 << " MB");
  CHECK(data + 0.85e6 < 5e6);
  const nlohmann::json d = viewcli_page_json(dir / "run/view.html");
  // 20 001 rows of 19 numbers (case 3 samples every 5 ms) exceed the 300 000-number budget:
  // every 2nd row is kept, the last one included.
  CHECK(d["trajectory"]["rows"] == 20001);
  CHECK(d["trajectory"]["every"] == 2);
  CHECK(d["trajectory"]["data"][0].size() == 10001);
  CHECK(d["trajectory"]["data"][0].back() == 100.0);
}
