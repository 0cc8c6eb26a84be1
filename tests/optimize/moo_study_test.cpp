// Multi-objective studies end to end (docs/pareto.md), on the shipped example
// studies/moo_impulse_example.json (impulse model, NSGA-II, 12 x 7 evaluations, well under a
// second): the reported front is the brute-force non-dominated set of the journal's feasible
// evaluations, its hypervolume and the driver's per generation agree with an independent
// 2-D sweep, the hypervolume never falls, 1 and 2 threads give the same journal and numbers,
// a truncated or killed run resumes to the same journal bytes and front, a front design
// reproduces bit for bit, bad input names its file and pointer (exit 2), a staged study ends
// with a multi-objective stage, and 2 MPI ranks give the threaded run's files.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/write/crash_point.hpp"
#include "optimize/moo_study.hpp"
#include "optimize/study.hpp"
#include "tests/cli/cli_support.hpp"

using nlohmann::json;
using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

namespace {

const std::string kStudy = std::string(PRONK_SOURCE_DIR) + "/studies/moo_impulse_example.json";

std::string load_error(const std::vector<std::string>& overrides, std::string* pointer) {
  try {
    (void)pronk::optimize::load_study(kStudy, overrides);
  } catch (const pronk::io::InputError& e) {
    *pointer = e.pointer();
    return e.what();
  }
  return "";
}

Run optimize(const TempDir& d, const std::string& out, const std::string& threads,
             bool resume = false) {
  std::vector<std::string> args = {"optimize", kStudy, "-q", "--threads", threads, "--out", d / out};
  if (resume) args.push_back("--resume");
  return cli_support::pronk(d, args);
}

std::vector<json> journal_records(const std::string& text) {
  std::vector<json> out;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) out.push_back(json::parse(line));
  return out;
}

bool dominates(const std::vector<double>& a, const std::vector<double>& b) {
  bool strictly = false;
  for (size_t j = 0; j < a.size(); ++j) {
    if (a[j] > b[j]) return false;
    if (a[j] < b[j]) strictly = true;
  }
  return strictly;
}

// The 2-D hypervolume by a sweep: points sorted by the first objective, each adding the
// rectangle between it, the next better second objective and the reference.
double hypervolume_2d(std::vector<std::vector<double>> pts, const std::vector<double>& r) {
  pts.erase(std::remove_if(pts.begin(), pts.end(),
                           [&](const auto& p) { return !(p[0] < r[0] && p[1] < r[1]); }),
            pts.end());
  std::sort(pts.begin(), pts.end());
  double hv = 0.0, best_y = r[1];
  for (const auto& p : pts) {
    if (p[1] >= best_y) continue;
    // p improves on the second objective: the strip from p's x to the reference.
    hv += (r[0] - p[0]) * (best_y - p[1]);
    best_y = p[1];
  }
  return hv;
}

std::vector<double> penalized(const json& rec, double weight) {
  std::vector<double> f = rec.at("objectives").get<std::vector<double>>();
  double p = 0.0;
  for (double g : rec.at("constraints").get<std::vector<double>>()) p += g > 0 ? g * g : 0.0;
  for (double& v : f) v += weight * p;
  return f;
}

}  // namespace

TEST_CASE("multi-objective studies: bad input names its file and pointer",
          "[moo-study][input]") {
  std::string pointer;
  CHECK(load_error({}, &pointer).empty());
  const std::vector<std::tuple<std::vector<std::string>, std::string, std::string>> cases = {
      {{"/objectives=[{\"name\": \"a\", \"terms\": [{\"metric\": \"x_error\"}]}]"},
       "/objectives",
       "/objectives: expected at least 2 objectives (a multi-objective algorithm needs at least "
       "2), found 1 entry"},
      {{"/optimizer/options/population=10"},
       "/optimizer/options/population",
       "/optimizer/options/population: expected a multiple of 4 of at least 8 (pagmo's nsga2 "
       "needs at least 5 individuals and a multiple of 4), found 10"},
      {{"/objectives/1/terms/0/metric=\"attitude\""},
       "/objectives/1/terms/0/metric",
       "/objectives/1/terms/0/metric: expected a metric name ("},
      {{"/parameters/0/pointer=\"/controller/kp/9\""}, "/parameters/0/pointer", ""},
      {{"/optimizer/algorithm=\"nsga3\""},
       "/optimizer/algorithm",
       "/optimizer/algorithm: expected a multi-objective algorithm of library pagmo (nsga2, "
       "moead, nspso) for a study with \"objectives\", found pagmo \"nsga3\""},
      {{"/optimizer/options/crossover=0.9"}, "/optimizer/options/crossover",
       "/optimizer/options/crossover: expected an option of"},
      {{"/optimizer/options/cr=1.5"}, "/optimizer/options/cr",
       "/optimizer/options/cr: expected a number in [0, 1), found 1.5"},
      {{"/optimizer/max_evaluations=100"}, "/optimizer/max_evaluations",
       "/optimizer/max_evaluations: expected no \"max_evaluations\" with a multi-objective"},
      {{"/objective=[{\"metric\": \"x_error\"}]"}, "/objective",
       "/objective: expected no \"objective\" beside \"objectives\""},
      {{"/objectives/1/name=\"tracking\""}, "/objectives/1/name",
       "/objectives/1/name: expected distinct objective names, found \"tracking\" twice"},
  };
  for (const auto& [overrides, ptr, message] : cases) {
    INFO(overrides.front());
    const std::string what = load_error(overrides, &pointer);
    CHECK(pointer == ptr);
    CHECK_THAT(what, Catch::StartsWith(kStudy + ": " + message));
  }
  // The single-objective form under a multi-objective algorithm: one objective is too few.
  json doc = json::parse(slurp(kStudy));
  doc.erase("objectives");
  doc["objective"] = json::parse(R"([{"metric": "x_error"}])");
  try {
    (void)pronk::optimize::parse_study(doc, kStudy, std::string(PRONK_SOURCE_DIR) + "/studies");
    FAIL("no error");
  } catch (const pronk::io::InputError& e) {
    CHECK(e.pointer() == "/objective");
    CHECK_THAT(e.what(), Catch::EndsWith("found 1 entry"));
  }
  // "objectives" under a single-objective algorithm.
  CHECK_THAT(load_error({"/optimizer/algorithm=\"cmaes\""}, &pointer),
             Catch::Contains("/optimizer/algorithm: expected a multi-objective algorithm of "
                             "library pagmo (nsga2, moead, nspso) for a study with \"objectives\", "
                             "found pagmo \"cmaes\""));

  // The command line: exit 2 and one line for each kind.
  TempDir d("moo_study_input");
  for (const std::string& set :
       {std::string("/optimizer/options/population=10"), std::string("/optimizer/algorithm=\"nsga3\""),
        std::string("/optimizer/options/foo=1"),
        std::string("/objectives/0/terms/0/metric=\"nothing\"")}) {
    INFO(set);
    const Run r = cli_support::pronk(d, {"optimize", kStudy, "--set", set, "--out", d / "out"});
    check_bad_input(r, kStudy + ": /");
  }
  CHECK_FALSE(std::filesystem::exists(d / "out"));
}

TEST_CASE("multi-objective studies: the front, hypervolumes, threads, resume and reproduce",
          "[moo-study]") {
  TempDir d("moo_study");
  const Run one = optimize(d, "t1", "1");
  INFO(one.err);
  REQUIRE(one.code == 0);
  const std::string journal = slurp(d / "t1/journal.jsonl");
  const json doc = json::parse(slurp(d / "t1/pareto.json"));
  const std::vector<json> records = journal_records(journal);
  REQUIRE(records.size() == 84);  // population 12, the first and 6 generations
  CHECK(doc.at("evaluations") == 84);
  CHECK(doc.at("optimizer").at("algorithm") == "nsga2");

  // The front is the brute-force non-dominated set of the feasible evaluations (first of equal
  // vectors kept), by evaluation index, each with the journal's objectives and constraints.
  std::vector<long> expected;
  for (size_t i = 0; i < records.size(); ++i) {
    const json& a = records[i];
    const auto g = a.at("constraints").get<std::vector<double>>();
    const bool feasible =
        a.at("ok").get<bool>() && std::all_of(g.begin(), g.end(), [](double v) { return v <= 1e-8; });
    if (!feasible) continue;
    const auto fa = a.at("objectives").get<std::vector<double>>();
    bool kept = true;
    for (size_t k = 0; k < records.size() && kept; ++k) {
      const json& b = records[k];
      const auto gb = b.at("constraints").get<std::vector<double>>();
      if (!b.at("ok").get<bool>() ||
          !std::all_of(gb.begin(), gb.end(), [](double v) { return v <= 1e-8; }))
        continue;
      const auto fb = b.at("objectives").get<std::vector<double>>();
      if (dominates(fb, fa) || (k < i && fb == fa)) kept = false;
    }
    if (kept) expected.push_back(static_cast<long>(i));
  }
  const json& front = doc.at("front");
  REQUIRE(front.size() == expected.size());
  REQUIRE(front.size() >= 2);
  std::vector<std::vector<double>> front_f;
  for (size_t k = 0; k < front.size(); ++k) {
    INFO("front design " << k);
    const long e = front[k].at("evaluation").get<long>();
    CHECK(e == expected[k]);
    const json& rec = records[static_cast<size_t>(e)];
    const std::vector<double> f = {front[k].at("objectives").at("tracking").get<double>(),
                                   front[k].at("objectives").at("attitude").get<double>()};
    CHECK(f == rec.at("objectives").get<std::vector<double>>());
    CHECK(front[k].at("constraints") == rec.at("constraints"));
    CHECK(front[k].at("unit") == rec.at("x"));
    const double stabilized = front[k].at("validation").at("stabilized").get<double>();
    const double fell = front[k].at("validation").at("fell").get<double>();
    CHECK(stabilized * 8 == std::round(stabilized * 8));  // a fraction of the 8 held-out starts
    CHECK(fell * 8 == std::round(fell * 8));
    front_f.push_back(f);
  }

  // Hypervolumes against an independent 2-D sweep: the front's, and the driver's per
  // generation (its archive of penalized objective vectors of every evaluation so far),
  // which never falls.
  const auto ref = doc.at("reference").get<std::vector<double>>();
  const auto hv = doc.at("hypervolume").get<std::vector<double>>();
  REQUIRE(hv.size() == 7);
  CHECK(doc.at("front_hypervolume").get<double>() ==
        Approx(hypervolume_2d(front_f, ref)).epsilon(1e-12));
  const double weight = doc.at("optimizer").at("penalty_weight").get<double>();
  for (size_t g = 0; g < hv.size(); ++g) {
    INFO("generation " << g);
    std::vector<std::vector<double>> archive;
    for (size_t i = 0; i < 12 * (g + 1); ++i) archive.push_back(penalized(records[i], weight));
    CHECK(hv[g] == Approx(hypervolume_2d(archive, ref)).epsilon(1e-12));
    if (g > 0) CHECK(hv[g] >= hv[g - 1]);
  }
  CHECK(hv.back() > hv.front());  // the run found better trade-offs than its first population
  const long knee = doc.at("knee").get<long>();
  CHECK(knee >= 0);
  CHECK(knee < static_cast<long>(front.size()));

  // pareto.csv: a header and one row per front design, the knee marked.
  const std::string csv = slurp(d / "t1/pareto.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == static_cast<long>(front.size()) + 1);
  CHECK(csv.rfind("front_index,evaluation,kp_x,kd_x,kp_roll,kd_roll,tracking,attitude,g0,knee,"
                  "validation_stabilized,validation_fell\n",
                  0) == 0);

  // 2 threads: the same journal bytes and the same numbers.
  const Run two = optimize(d, "t2", "2");
  REQUIRE(two.code == 0);
  CHECK(slurp(d / "t2/journal.jsonl") == journal);
  json a = doc, b = json::parse(slurp(d / "t2/pareto.json"));
  for (json* j : {&a, &b}) {
    j->erase("threads");
    j->erase("wall_time_s");
  }
  CHECK(a == b);

  // A journal truncated in the middle of a line (as a kill mid-write leaves it) resumes to
  // the same journal bytes and the same front.
  std::filesystem::create_directories(d / "cut");
  const std::size_t cut = journal.find('\n', journal.size() / 3) + 40;
  write_file(d / "cut/journal.jsonl", journal.substr(0, cut));
  const Run resumed = optimize(d, "cut", "2", true);
  INFO(resumed.err);
  REQUIRE(resumed.code == 0);
  CHECK(slurp(d / "cut/journal.jsonl") == journal);
  const json c = json::parse(slurp(d / "cut/pareto.json"));
  CHECK(c.at("front") == doc.at("front"));
  CHECK(c.at("hypervolume") == doc.at("hypervolume"));
  CHECK(c.at("knee") == doc.at("knee"));

  // Killed at a crash point (PRONK_CRASH_AT: std::_Exit as kill -9 would) inside the fourth
  // population, then resumed on 1 thread.
  ::setenv("PRONK_CRASH_AT", "45", 1);
  const Run killed = optimize(d, "k45", "2");
  ::unsetenv("PRONK_CRASH_AT");
  CHECK(killed.code == pronk::io::kCrashExitCode);
  const std::string partial = slurp(d / "k45/journal.jsonl");
  CHECK(journal.rfind(partial.substr(0, partial.rfind('\n') + 1), 0) == 0);
  const Run again = optimize(d, "k45", "1", true);
  INFO(again.err);
  REQUIRE(again.code == 0);
  CHECK(slurp(d / "k45/journal.jsonl") == journal);
  CHECK(json::parse(slurp(d / "k45/pareto.json")).at("front") == doc.at("front"));

  // Every front design reproduces bit for bit on this build; an index past the front is bad
  // input.
  for (size_t k = 0; k < front.size(); ++k) {
    const Run rep = cli_support::pronk(
        d, {"reproduce", d / "t1/pareto.json", "--front-index", std::to_string(k)});
    INFO(rep.out << rep.err);
    CHECK(rep.code == 0);
    CHECK_THAT(rep.out, Catch::Contains("reproduced: 0 of"));
  }
  // On another build (the recorded commit changed): each value within the tolerance its
  // design's perturbation run recorded; a value moved beyond it is a mismatch (exit 1).
  json other = doc;
  other["commit"] = "another-commit";
  for (const json& f : other.at("front")) {
    const json& t = f.at("reproduction").at("tolerance");
    CHECK(t.at("objectives").size() == 2);
    CHECK(t.at("constraints").size() == 1);
    CHECK(t.at("metrics").contains("mean(x_error)"));
    CHECK(f.at("reproduction").at("validation").at("tolerance").is_object());
  }
  write_file(d / "other.json", other.dump());
  const Run tolerant =
      cli_support::pronk(d, {"reproduce", d / "other.json", "--front-index", "0"});
  INFO(tolerant.out << tolerant.err);
  CHECK(tolerant.code == 0);
  CHECK_THAT(tolerant.out, Catch::Contains("another build: each value within the tolerance"));
  const double x = other["front"][0]["objectives"]["tracking"].get<double>();
  other["front"][0]["objectives"]["tracking"] = x * (1 + 1e-3);
  write_file(d / "moved.json", other.dump());
  const Run moved = cli_support::pronk(d, {"reproduce", d / "moved.json", "--front-index", "0"});
  CHECK(moved.code == 1);
  CHECK_THAT(moved.out, Catch::Contains("NOT REPRODUCED: 1 of"));

  const Run past = cli_support::pronk(d, {"reproduce", d / "t1/pareto.json", "--front-index",
                                          std::to_string(front.size())});
  check_bad_input(past, d / "t1/pareto.json" + ": /front: expected a front with an index");
}

TEST_CASE("multi-objective studies: a staged study may end with a multi-objective stage",
          "[moo-study][staged]") {
  TempDir d("moo_staged");
  // The example's problem: a single-objective BOBYQA stage, then its objectives by NSGA-II.
  json example = json::parse(slurp(kStudy));
  json staged = example;
  staged["name"] = "moo_staged";
  staged["scene"] = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case2_legged_impulse.json";
  staged.erase("objectives");
  staged["objective"] = json::parse(R"([{"metric": "x_error"}, {"metric": "attitude_error"}])");
  staged["optimizer"] = json::parse(
      R"({"library": "nlopt", "algorithm": "LN_BOBYQA", "max_evaluations": 12, "seed": 3})");
  staged["stages"] = json::array(
      {json{{"name", "single"}, {"model", "impulse"}},
       json{{"name", "front"},
            {"model", "impulse"},
            {"objectives", example.at("objectives")},
            {"optimizer", example.at("optimizer")}}});
  write_file(d / "staged.json", staged.dump(1));
  const Run r = cli_support::pronk(d, {"optimize", d / "staged.json", "-q", "--threads", "2",
                                       "--out", d / "out"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(std::filesystem::exists(d / "out/stages/1_single/design.json"));
  const json top = json::parse(slurp(d / "out/pareto.json"));
  CHECK(slurp(d / "out/pareto.json") == slurp(d / "out/stages/2_front/pareto.json"));
  CHECK(top.at("evaluations") == 84);
  REQUIRE(top.at("front").size() >= 2);
  // The stage's study document carries the first stage's design for the parameters it
  // does not tune (here it tunes them all), and the front reproduces from it.
  const Run rep =
      cli_support::pronk(d, {"reproduce", d / "out/pareto.json", "--front-index", "0"});
  INFO(rep.out << rep.err);
  CHECK(rep.code == 0);

  // Only the last stage may be multi-objective.
  staged["stages"].push_back(json{{"name", "after"}, {"model", "impulse"}});
  write_file(d / "bad.json", staged.dump(1));
  const Run bad = cli_support::pronk(d, {"optimize", d / "bad.json", "--out", d / "bad"});
  check_bad_input(bad, d / "bad.json" + ": /stages/1/optimizer/algorithm: expected a "
                                        "single-objective optimizer (only the last stage");
}

#ifdef PRONK_MPIEXEC
TEST_CASE("multi-objective studies: 2 MPI ranks give the threaded run's journal and front",
          "[moo-study][mpi]") {
  TempDir d("moo_mpi");
  const Run threads = optimize(d, "threads", "2");
  REQUIRE(threads.code == 0);
  std::string cmd = "cd " + quote(d.path) + " && ASAN_OPTIONS=detect_leaks=0 ";
  cmd += PRONK_MPIEXEC;
  cmd += " -x ASAN_OPTIONS --allow-run-as-root --oversubscribe -np 2 ";
  cmd += quote(PRONK_EXE) + " optimize " + quote(kStudy) + " --out " + quote(d / "mpi");
  cmd += " >" + quote(d / ".stdout") + " 2>" + quote(d / ".stderr");
  const int status = std::system(cmd.c_str());
  INFO(slurp(d / ".stderr"));
  REQUIRE(status == 0);
  CHECK(slurp(d / ".stdout").find("2 MPI ranks") != std::string::npos);
  CHECK(slurp(d / "mpi/journal.jsonl") == slurp(d / "threads/journal.jsonl"));
  json a = json::parse(slurp(d / "threads/pareto.json"));
  json b = json::parse(slurp(d / "mpi/pareto.json"));
  for (json* j : {&a, &b}) {
    j->erase("threads");
    j->erase("wall_time_s");
  }
  CHECK(a == b);
}
#endif
