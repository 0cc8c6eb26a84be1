// End-to-end tests of `pronk map`: bad input (exit 2, one line naming file and
// pointer), a tiny map written with every output file, and — when MPI is
// built — `mpirun -np 2 pronk map` giving the threaded run's bytes.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "sim/scene/scene.hpp"
#include "tests/optimize/map/map_test_support.hpp"

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Dir {
  std::string path;
  Dir() {
    char t[] = "/tmp/pronk_map_cli_XXXXXX";
    REQUIRE(::mkdtemp(t) != nullptr);
    path = t;
  }
  ~Dir() {
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

int run(const std::string& command, const std::string& dir, std::string* err = nullptr) {
  const std::string e = dir + "/stderr.txt";
  const int rc = std::system((command + " > " + dir + "/stdout.txt 2> " + e).c_str());
  if (err) *err = slurp(e);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string pronk_exe() { return std::string(PRONK_EXE); }

}  // namespace

TEST_CASE("map rejects bad input with exit 2 naming file and pointer", "[cli][map]") {
  Dir d;
  std::string err;
  CHECK(run(pronk_exe() + " map " + d.path + "/missing.json", d.path, &err) == 2);
  CHECK(err.find("missing.json") != std::string::npos);
  json doc = pronk::test::tiny_map_document();
  doc["axes"][0]["scael"] = "log";
  { std::ofstream(d.path + "/bad.json") << doc.dump(); }
  CHECK(run(pronk_exe() + " map " + d.path + "/bad.json --out " + d.path + "/o", d.path, &err) ==
        2);
  CHECK(err.rfind("pronk: error: " + d.path + "/bad.json: /axes/0/scael: expected a known key",
                  0) == 0);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(d.path + "/o/journal.jsonl"));
  // A model name that is none of the three (pseudo_rigid is one: the robot in the full model).
  doc = pronk::test::tiny_map_document();
  doc["models"] = {"pulse", "pseudo-rigid"};
  { std::ofstream(d.path + "/model.json") << doc.dump(); }
  CHECK(run(pronk_exe() + " map " + d.path + "/model.json --out " + d.path + "/o", d.path, &err) ==
        2);
  CHECK(err.rfind("pronk: error: " + d.path +
                      "/model.json: /models/1: expected \"impulse\", \"pulse\"" +
                      (pronk::scene::mujoco_available()
                           ? std::string(", \"pseudo_rigid\" or \"mujoco\"")
                           : std::string(" or \"pseudo_rigid\" (this pronk was built without "
                                         "MuJoCo: install Debian's libmujoco-dev, e.g. with "
                                         "bash scripts/setup.sh, and rebuild for \"mujoco\")")) +
                      ", found string \"pseudo-rigid\"",
                  0) == 0);
  CHECK_FALSE(fs::exists(d.path + "/o/journal.jsonl"));
  { std::ofstream(d.path + "/good.json") << pronk::test::tiny_map_document().dump(); }
  CHECK(run(pronk_exe() + " map " + d.path + "/good.json --set /trials/count=0", d.path, &err) ==
        2);
  CHECK(err.find("/trials/count: expected") != std::string::npos);
  CHECK(run(pronk_exe() + " map --threads 0 " + d.path + "/good.json", d.path) == 2);
  CHECK(run(pronk_exe() + " map " + d.path + "/good.json --bogus", d.path) == 2);
}

TEST_CASE("map writes every output file and --resume recomputes nothing", "[cli][map]") {
  Dir d;
  { std::ofstream(d.path + "/s.json") << pronk::test::tiny_map_document(3, 2, 5.0).dump(); }
  const std::string out = d.path + "/out";
  REQUIRE(run(pronk_exe() + " map " + d.path + "/s.json --threads 2 --out " + out, d.path) == 0);
  for (const char* f : {"cells.csv", "trials.csv", "boundary.csv", "summary.json", "fraction.gp",
                        "disagreement.gp", "journal.jsonl"})
    CHECK(fs::exists(out + "/" + f));
  const json summary = json::parse(slurp(out + "/summary.json"));
  CHECK(summary["type"] == "pronk_map");
  CHECK(summary["totals"]["cells"] == 6);
  CHECK(summary["boundary"]["rows"].size() == 2);
  CHECK(summary["spectral_radius_method"] == "stride map linearised by central differences");
  // Each row's boundary, on stdout: a value, or (none_good) a sentence without one.
  const std::string printed = slurp(d.path + "/stdout.txt");
  CHECK(printed.find("  boundary row 0: ") != std::string::npos);
  CHECK(printed.find("  boundary row 1: ") != std::string::npos);
  CHECK(printed.find("none_good duty_cycle =") == std::string::npos);
  const std::string cells = slurp(out + "/cells.csv");
  REQUIRE(run(pronk_exe() + " map " + d.path + "/s.json --resume --out " + out, d.path) == 0);
  CHECK(slurp(d.path + "/stdout.txt").find("(0 computed, 6 from the journal)") !=
        std::string::npos);
  CHECK(slurp(out + "/cells.csv") == cells);
}

TEST_CASE("map runs the robot in the full model: pulse vs pseudo_rigid",
          "[cli][map][pseudo_rigid][heavy]") {
  // One cell, one 6 s trial at 10 % duty (about a second of the full model), no stride map.
  Dir d;
  json doc = pronk::test::tiny_map_document(1, 1, 6.0);
  doc["models"] = {"pulse", "pseudo_rigid"};
  doc["scene_overrides"].push_back(R"(/pseudo_rigid={"legs": "force", "internal_stiffness": 1e6, )"
                                   R"("position_trim_gain": 0, "attitude_trim_gain": 0})");
  doc["axes"] = {{{"kind", "duty_cycle"}, {"values", {0.1}}}};
  doc["stability"] = false;
  { std::ofstream(d.path + "/s.json") << doc.dump(); }
  std::string err;
  REQUIRE(run(pronk_exe() + " map " + d.path + "/s.json --out " + d.path + "/out", d.path, &err) ==
          0);
  const json summary = json::parse(slurp(d.path + "/out/summary.json"));
  CHECK(summary["models"] == json({"pulse", "pseudo_rigid"}));
  CHECK(summary["primary_model"] == "pseudo_rigid");
  CHECK(summary["spectral_radius_method"] == "off");
  // The two models judge this trial alike (see the engine test for the reasons).
  CHECK(summary["totals"]["disagreements"] == 0);
  CHECK(summary["disagreement"]["first_disagreement"].is_null());
  // stderr is a file: the progress is plain lines with the time elapsed (the last: done).
  CHECK_THAT(err, Catch::Matchers::Contains(": cells 1/1, ") &&
                      Catch::Matchers::Contains(" elapsed, done"));
  CHECK(err.find('\r') == std::string::npos);
  CHECK_THAT(slurp(d.path + "/stdout.txt"),
             Catch::Matchers::Contains("disagreements pulse vs pseudo_rigid: 0 trials; none "
                                       "anywhere on the grid (duty_cycle up to 0.1)"));
  CHECK(summary["totals"]["stabilized_fraction"]["pulse"] ==
        summary["totals"]["stabilized_fraction"]["pseudo_rigid"]);
  const std::string cells = slurp(d.path + "/out/cells.csv");
  CHECK(cells.find("stabilized_pulse,stabilized_pseudo_rigid,disagreements,pulse_only,"
                   "pseudo_rigid_only") != std::string::npos);
}

#ifdef PRONK_MPIEXEC
/// `mpirun -np 2` as root on a 2-core machine. OpenMPI 4.1 leaks in its own start-up and
/// in the plugins it unloads, which LeakSanitizer (in the sanitizer build) reports as an
/// exit status of 1: leak checking is switched off for the ranks only (-x passes it on);
/// address and undefined-behaviour checks stay on, and every other test checks leaks.
std::string mpirun_np2() {
  std::string cmd = "ASAN_OPTIONS=detect_leaks=0 ";
  cmd.append(PRONK_MPIEXEC);
  cmd.append(" -x ASAN_OPTIONS --allow-run-as-root --oversubscribe -np 2 ");
  return cmd;
}

TEST_CASE("mpirun -np 2 pronk map writes the threaded run's bytes", "[cli][map][mpi]") {
  Dir d;
  { std::ofstream(d.path + "/s.json") << pronk::test::tiny_map_document(4, 2, 5.0).dump(); }
  REQUIRE(
      run(pronk_exe() + " map " + d.path + "/s.json -q --threads 2 --out " + d.path + "/threads",
          d.path) == 0);
  std::string err;
  const int rc =
      run(mpirun_np2() + pronk_exe() + " map " + d.path + "/s.json --out " + d.path + "/mpi",
          d.path, &err);
  INFO(err);
  REQUIRE(rc == 0);
  CHECK(slurp(d.path + "/stdout.txt").find("on 2 MPI ranks") != std::string::npos);
  for (const char* f : {"cells.csv", "trials.csv", "boundary.csv", "summary.json", "fraction.gp",
                        "disagreement.gp"}) {
    INFO(f);
    CHECK(slurp(d.path + "/threads/" + f) == slurp(d.path + "/mpi/" + f));
  }
  // Bad input under MPI: rank 0 reports it once, every rank exits.
  CHECK(run(mpirun_np2() + pronk_exe() + " map " + d.path + "/s.json --set /trials/cuont=1", d.path,
            &err) == 2);
  // (mpirun adds its own note about the non-zero exit code.)
  const size_t first = err.find("pronk: error: ");
  CHECK(first != std::string::npos);
  CHECK(err.find("/trials/cuont: expected a known key") != std::string::npos);
  CHECK(err.find("pronk: error: ", first + 1) == std::string::npos);
}

TEST_CASE("mpirun -np 2 pronk map: a task that throws is reported once by rank 0",
          "[cli][map][mpi]") {
  // Every value is valid alone, but no combination is (a start below the fall
  // height): every cell throws io::InputError while it is computed, on whichever
  // rank; rank 0 reports the first one as bad input (exit 2), once, and every rank exits.
  Dir d;
  json doc = pronk::test::tiny_map_document(2, 1, 1.0);
  doc["axes"] = {
      {{"kind", "pointer"}, {"pointer", "/initial/position/2"}, {"values", {0.2, 0.3}}},
      {{"kind", "pointer"}, {"pointer", "/simulation/fall/min_height"}, {"values", {0.35, 0.4}}}};
  { std::ofstream(d.path + "/s.json") << doc.dump(); }
  std::string err;
  CHECK(run(pronk_exe() + " map " + d.path + "/s.json -q --out " + d.path + "/threads", d.path,
            &err) == 2);
  CHECK(err.find("/initial/position/2: expected a CoM height above the fall height") !=
        std::string::npos);
  CHECK(run(mpirun_np2() + pronk_exe() + " map " + d.path + "/s.json -q --out " + d.path + "/mpi",
            d.path, &err) == 2);
  const size_t first = err.find("pronk: error: ");
  CHECK(first != std::string::npos);
  CHECK(err.find("/initial/position/2: expected a CoM height above the fall height") !=
        std::string::npos);
  CHECK(err.find("pronk: error: ", first + 1) == std::string::npos);
}
#endif
