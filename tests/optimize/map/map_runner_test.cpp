// Running maps: bit-identical outputs for any thread count, --resume from a
// torn journal equals the uninterrupted run, a journal of another study is
// refused, and the shipped seed study reproduces the seed's duty-cycle limit.
#include "optimize/map/map_runner.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "optimize/map/map_output.hpp"
#include "io/load/input_error.hpp"
#include "tests/optimize/map/map_test_support.hpp"

namespace m = pronk::optimize::map;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  std::string path;
  TempDir() {
    char t[] = "/tmp/pronk_map_test_XXXXXX";
    REQUIRE(::mkdtemp(t) != nullptr);
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* kOutputs[] = {"cells.csv",    "trials.csv",  "boundary.csv",
                          "summary.json", "fraction.gp", "disagreement.gp"};

m::MapOutcome run(const m::MapStudy& st, const std::string& dir, int threads, bool resume = false) {
  m::MapRunOptions opt;
  opt.threads = threads;
  opt.out_dir = dir;
  opt.resume = resume;
  opt.figures = false;
  return m::run_map(st, opt);
}

}  // namespace

TEST_CASE("map outputs are bit-identical for 1 and 2 threads", "[map][determinism]") {
  TempDir d;
  const m::MapStudy st = pronk::test::tiny_map(4, 3, 6.0);
  const m::MapOutcome a = run(st, d.path + "/t1", 1);
  const m::MapOutcome b = run(st, d.path + "/t2", 2);
  REQUIRE(a.status == "completed");
  REQUIRE(b.status == "completed");
  CHECK(a.cells_computed == st.cells());
  for (const char* f : kOutputs) {
    INFO(f);
    CHECK(slurp(d.path + "/t1/" + f) == slurp(d.path + "/t2/" + f));
  }
  // cells.csv agrees with the summaries; every row has a boundary.
  CHECK(a.boundaries.size() == 2);
  const std::string cells = slurp(d.path + "/t1/cells.csv");
  CHECK(cells.rfind("cell,row,column,duty_cycle,tilt_deg,trials,stabilized_impulse,", 0) == 0);
  CHECK(std::count(cells.begin(), cells.end(), '\n') == st.cells() + 1);
  const std::string trials = slurp(d.path + "/t1/trials.csv");
  CHECK(std::count(trials.begin(), trials.end(), '\n') == st.cells() * st.trials.count + 1);
}

TEST_CASE("resuming from a torn journal gives the uninterrupted run's outputs", "[map][journal]") {
  TempDir d;
  const m::MapStudy st = pronk::test::tiny_map(4, 2, 6.0);
  const m::MapOutcome full = run(st, d.path + "/full", 2);
  REQUIRE(full.status == "completed");
  // An interrupted run: the header, 3 cell records, and half a line.
  const std::string journal = slurp(d.path + "/full/journal.jsonl");
  std::istringstream lines(journal);
  std::string line, kept;
  for (int i = 0; i < 4 && std::getline(lines, line); ++i) kept += line + "\n";
  std::getline(lines, line);
  kept += line.substr(0, line.size() / 2);
  fs::create_directories(d.path + "/resumed");
  { std::ofstream(d.path + "/resumed/journal.jsonl", std::ios::binary) << kept; }
  const m::MapOutcome r = run(st, d.path + "/resumed", 1, true);
  REQUIRE(r.status == "completed");
  CHECK(r.cells_replayed == 3);
  CHECK(r.cells_computed == st.cells() - 3);
  for (const char* f : kOutputs) {
    INFO(f);
    CHECK(slurp(d.path + "/full/" + f) == slurp(d.path + "/resumed/" + f));
  }
  // A second resume replays everything and computes nothing.
  const m::MapOutcome again = run(st, d.path + "/resumed", 1, true);
  CHECK(again.cells_computed == 0);
  CHECK(again.rows_bisected == 0);
  CHECK(slurp(d.path + "/full/cells.csv") == slurp(d.path + "/resumed/cells.csv"));
  // The journal of another study is refused.
  const m::MapStudy other = pronk::test::tiny_map(5, 2, 6.0);
  CHECK_THROWS_AS(run(other, d.path + "/resumed", 1, true), pronk::io::InputError);
}

TEST_CASE("a stop request ends the map with the journal kept", "[map][journal]") {
  TempDir d;
  const m::MapStudy st = pronk::test::tiny_map(4, 2, 6.0);
  std::atomic<bool> stop{true};
  m::MapRunOptions opt;
  opt.out_dir = d.path;
  opt.stop_flag = &stop;
  opt.figures = false;
  const m::MapOutcome o = m::run_map(st, opt);
  CHECK(o.status == "stopped");
  CHECK(fs::exists(d.path + "/journal.jsonl"));
  CHECK_FALSE(fs::exists(d.path + "/cells.csv"));
  m::MapRunOptions bad;
  bad.threads = 0;
  CHECK(bad.validate().find("threads") != std::string::npos);
}

// Ridgely 2001, §2.6.1, with the shipped study: the seed's controller and gains, impulse vs
// pulse model, duty 10-50 % in steps of 1 %. Measured threshold (docs/maps.md): in the
// rows with no and with 5 deg extra initial tilt the impulse model stabilizes
// every trial; no trial is judged differently by the two models up to 27 %
// duty, and every cell from 29 % on has disagreements (first at 29 % and 28 %).
// Larger extra tilts lower it (18 % at 20 deg); below 18 % no row disagrees.
TEST_CASE("Ridgely 2001, §2.6.1: no impulse/pulse disagreement below ~30 % duty, some above",
          "[map][seed]") {
  TempDir d;
  const m::MapStudy st =
      m::load_map_study(std::string(PRONK_SOURCE_DIR) + "/studies/map_seed_duty.json");
  m::MapRunOptions opt;
  opt.threads = 2;
  opt.out_dir = d.path;
  opt.figures = false;
  const m::MapOutcome o = m::run_map(st, opt);
  REQUIRE(o.status == "completed");
  for (long row : {0L, 1L}) {
    for (long col = 0; col < st.columns(); ++col) {
      const m::CellSummary& c = o.summaries[static_cast<size_t>(row * st.columns() + col)];
      INFO("row " << row << " duty " << c.value0);
      if (c.value0 <= 0.275) CHECK(c.disagreements == 0);
      if (c.value0 >= 0.285) CHECK(c.disagreements > 0);
      CHECK(c.fraction[0] == 1.0);  // the impulse model stabilizes every trial
    }
  }
  // Over every row, no disagreement at low duty.
  for (const auto& c : o.summaries)
    if (c.value0 <= 0.175) CHECK(c.disagreements == 0);
  // The committed results say the same.
  const nlohmann::json committed = nlohmann::json::parse(
      slurp(std::string(PRONK_SOURCE_DIR) + "/results/map_seed_duty/summary.json"));
  CHECK(committed["disagreement"] == o.summary["disagreement"]);
  const auto& rows = committed["boundary"]["rows"];
  REQUIRE(rows.size() == o.boundaries.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    CHECK(rows[r]["status"] == o.boundaries[r].status);
    CHECK(rows[r]["boundary"].get<double>() == Approx(o.boundaries[r].boundary).margin(1e-9));
  }
}
