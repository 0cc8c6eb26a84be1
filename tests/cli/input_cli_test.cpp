// Bad input that used to get through, end to end: names that would lead outside the
// output root, a key given twice, bytes after the document, parameter and axis pointers
// nlohmann cannot resolve, an output directory the file system refuses, and CLI11's
// option errors. Each is exit 2 and one "pronk: error:" line naming where.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kStudies = std::string(PRONK_SOURCE_DIR) + "/studies/";
const std::string kScene = kStudies + "scenes/case1_body_only.json";
const std::string kMechanism = kStudies + "mechanisms/pendulum.json";
const std::string kStudy = kStudies + "study1_body_only_gains.json";
const std::string kStaged = kStudies + "study5_fidelity_gap.json";
const std::string kMap = kStudies + "map_seed_duty.json";
const std::string kDesign =
    std::string(PRONK_SOURCE_DIR) + "/results/study2_legged_pulse_duty50/design.json";

/// The entries of `dir` (names), sorted.
std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("a name that is not a plain directory name is bad input in every loader",
          "[cli][input]") {
  // "out/.." and "results/.." are the working directory itself: nothing may appear in it.
  TempDir work("input");
  struct Case {
    std::vector<std::string> args;  // the command up to --set
    std::string file;               // the file the error names
  };
  const std::vector<Case> cases = {{{"simulate", kScene}, kScene},
                                   {{"simulate", kMechanism}, kMechanism},
                                   {{"optimize", kStudy}, kStudy},
                                   {{"optimize", kStaged}, kStaged},
                                   {{"map", kMap}, kMap}};
  for (const Case& c : cases) {
    for (const char* name : {"..", ".", "", "a/b", "tab\there"}) {
      std::vector<std::string> args = c.args;
      args.insert(args.end(), {"--set", "/name=" + json(name).dump(), "-q"});
      INFO(args[0] << " " << args[1] << " name " << json(name).dump());
      check_bad_input(cli_support::pronk(work, args),
                      c.file + ": /name: expected a name usable as a directory name");
      CHECK(entries(work.path) == std::vector<std::string>{".stderr", ".stdout"});
    }
  }
}

TEST_CASE("a key given twice is bad input in every loader, naming the key", "[cli][input]") {
  TempDir d("input");
  struct Case {
    std::string command, source;
  };
  for (const Case& c :
       {Case{"simulate", kScene}, Case{"simulate", kMechanism}, Case{"optimize", kStudy},
        Case{"optimize", kStaged}, Case{"map", kMap}, Case{"reproduce", kDesign}}) {
    INFO(c.command << " " << c.source);
    const std::string text = slurp(c.source);
    // The document's first key once more, before all the others.
    const std::string key = json::parse(text).begin().key();
    write_file(d / "dup.json", "{\"" + key + "\": 0, " + text.substr(text.find('{') + 1));
    check_bad_input(cli_support::pronk(d, {c.command, "dup.json"}),
                    "dup.json: /" + key + ": expected each key once in an object, found \"" + key +
                        "\" a second time");
    // A NUL byte and then anything: the parser used to stop at the NUL.
    write_file(d / "nul.json", text + std::string(1, '\0') + "{\"garbage\": [");
    check_bad_input(cli_support::pronk(d, {c.command, "nul.json"}),
                    "nul.json: /: expected JSON without NUL bytes, found a NUL byte at byte "
                    "offset " +
                        std::to_string(text.size()));
    write_file(d / "two.json", text + text);
    check_bad_input(cli_support::pronk(d, {c.command, "two.json"}),
                    "two.json: /: expected valid JSON, found a syntax error");
  }
  // In a --set value, the duplicate's pointer is below the --set pointer.
  check_bad_input(
      cli_support::pronk(d, {"simulate", kScene, "--set", R"(/body={"mass": 1, "mass": 2})"}),
      R"(command line (--set /body={"mass": 1, "mass": 2}): /body/mass: expected )"
      "each key once in an object");
}

TEST_CASE("a pointer in the scene file's form says what the resolved scene calls it",
          "[cli][input]") {
  // The docs write the inertia as three numbers; studies, maps and perturbations bind to
  // the resolved scene, which holds the tensor.
  TempDir d("input");
  const std::string set = "/parameters/0/pointer=\"/body/inertia/1\"";
  const std::string expected =
      ": /parameters/0/pointer: expected a pointer to a number of the scene format (see "
      "scene.resolved.json), found \"/body/inertia/1\", which names no number of a scene; the "
      "resolved scene names this principal moment /body/inertia_tensor/1/1";
  check_bad_input(cli_support::pronk(d, {"optimize", kStudy, "--set", set}), kStudy + expected);
  check_bad_input(cli_support::pronk(d, {"optimize", kStaged, "--set", set}), kStaged + expected);
  const std::string axis =
      R"(/axes/1={"kind": "pointer", "pointer": "/body/inertia/0", "range": [1, 2], "count": 2})";
  check_bad_input(cli_support::pronk(d, {"map", kMap, "--set", axis}),
                  kMap +
                      ": /axes/1/pointer: expected a pointer to a number of the resolved scene, "
                      "found \"/body/inertia/0\" (no such value; the resolved scene names this "
                      "principal moment /body/inertia_tensor/0/0)");
}

TEST_CASE("parameter and axis pointers nlohmann cannot resolve are bad input", "[cli][input]") {
  TempDir d("input");
  for (const std::string ptr : {"/controller/kp/", "/controller/kp/99999999999999999999999",
                                "/controller/kp/01", "/controller/kp/-", "/controller/kp/0/"}) {
    INFO(ptr);
    const std::string set = "/parameters/0/pointer=" + json(ptr).dump();
    const std::string expected =
        ": /parameters/0/pointer: expected a pointer to a number of the "
        "scene format (see scene.resolved.json), found \"" +
        ptr + "\", which names no number of a scene";
    check_bad_input(cli_support::pronk(d, {"optimize", kStudy, "--set", set}), kStudy + expected);
    check_bad_input(cli_support::pronk(d, {"optimize", kStaged, "--set", set}), kStaged + expected);
    const std::string axis = R"(/axes/1={"kind": "pointer", "pointer": )" + json(ptr).dump() +
                             R"(, "range": [1, 2], "count": 2})";
    check_bad_input(cli_support::pronk(d, {"map", kMap, "--set", axis}),
                    kMap +
                        ": /axes/1/pointer: expected a pointer to a number of the resolved "
                        "scene, found \"" +
                        ptr + "\" (no such value)");
    // --set itself: the parent must exist.
    check_bad_input(cli_support::pronk(d, {"simulate", kScene, "--set", ptr + "/x=1"}),
                    "command line (--set " + ptr + "/x=1): " + ptr +
                        "/x: expected a pointer whose parent exists in the scene");
  }
}

TEST_CASE("an output directory the file system refuses is bad input for every command",
          "[cli][input]") {
  TempDir d("input");
  // root passes access(2) on /proc, but nothing can be created there.
  for (const std::string out : {"/proc/pronk", "/proc/pronk/deeper", "/proc"}) {
    for (std::vector<std::string> args :
         std::vector<std::vector<std::string>>{{"simulate", kScene},
                                               {"simulate", kMechanism},
                                               {"optimize", kStudy},
                                               {"map", kMap},
                                               {"bench", "--quick"}}) {
      args.insert(args.end(), {"--out", out});
      INFO(args[0] << " --out " << out);
      const Run r = cli_support::pronk(d, args);
      check_bad_input(r,
                      "--out: /: expected a directory that exists or can be created, found "
                      "\"/proc\", a directory in which nothing can be created (");
    }
  }
  // The check creates a probe directory and removes it: nothing is left behind.
  fs::create_directory(d / "existing");
  for (const std::string out : {"new", "existing"}) {
    const Run r = cli_support::pronk(
        d, {"simulate", kScene, "--set", "/simulation/duration=0.2", "--out", out, "-q"});
    CHECK(r.code == 0);
    CHECK(fs::exists(d / out + "/summary.json"));
  }
  CHECK(entries(d.path) == std::vector<std::string>{".stderr", ".stdout", "existing", "new"});
  for (const std::string out : {"new", "existing"}) {
    for (const std::string& name : entries(d / out)) CHECK_THAT(name, !StartsWith(".pronk"));
  }
}

TEST_CASE("option errors are one bad-input line", "[cli][input]") {
  TempDir d("input");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"optimize", kStudy, "--threads", "0"}, "--threads: Value 0 not in range 1 to 1024"},
      {{"map", kMap, "--threads", "2000"}, "--threads: Value 2000 not in range 1 to 1024"},
      {{"bench", "--repeat", "0"}, "--repeat: Value 0 not in range 1 to 1000"},
      {{"simulate", kScene, "--bogus"}, "The following argument was not expected: --bogus"},
      {{"simulate", kScene, "--model", "spring"}, "--model: spring not in"},
      {{"fly"}, "A subcommand is required"},
      {{}, "A subcommand is required"},
      {{"simulate"}, "scene is required"}};
  for (const auto& [args, message] : cases) {
    INFO(args.size());
    const Run r = cli_support::pronk(d, args);
    check_bad_input(r,
                    "command line: /: expected options as `pronk COMMAND --help` lists them, "
                    "found ");
    CHECK_THAT(r.err, Contains(message));
    CHECK(r.out.empty());
  }
  // reproduce reads --rtol itself (a design's own tolerances apply without it).
  for (const char* rtol : {"inf", "nan", "-1"}) {
    check_bad_input(
        cli_support::pronk(d, {"reproduce", kDesign, "--rtol", rtol}),
        std::string("--rtol: /: expected a finite relative tolerance > 0, found ") + rtol);
  }
  CHECK(entries(d.path) == std::vector<std::string>{".stderr", ".stdout"});
}
