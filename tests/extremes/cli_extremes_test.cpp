// What `pronk simulate` itself reports at the extremes: the exit code, the
// warnings in summary.json and on stdout, and no NaN in any output file.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  std::string path;
  TempDir() {
    char tmpl[] = "/tmp/pronk_extremes_test_XXXXXX";
    const char* p = ::mkdtemp(tmpl);
    REQUIRE(p != nullptr);
    path = p;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return path + "/" + name; }
};

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

struct Run {
  int code = -1;
  std::string out;
};

/// Runs pronk with args in dir; stdout captured.
Run pronk(const TempDir& dir, const std::vector<std::string>& args) {
  std::string cmd = "cd " + quote(dir.path) + " && exec " + quote(PRONK_EXE);
  for (const auto& a : args) cmd += ' ' + quote(a);
  cmd += " >" + quote(dir / ".stdout") + " 2>" + quote(dir / ".stderr") + " </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.out = slurp(dir / ".stdout");
  return r;
}

/// No "nan" or "inf" token in any output file of the run directory.
void check_no_nan(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.ends_with(".csv") || name.ends_with(".json")) {
      INFO(name);
      const std::string text = slurp(e.path().string());
      CHECK(text.find("nan") == std::string::npos);
      CHECK(text.find("inf") == std::string::npos);
    }
  }
}

}  // namespace

TEST_CASE("extreme CLI: a flexing, penetrating mechanism warns in summary.json and on stdout",
          "[extremes][cli]") {
  TempDir dir;
  const Run r = pronk(
      dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/four_leg_drop.json",
            "--set", "/simulation/t_end=0.3", "--out", dir / "out"});
  CHECK(r.code == 0);  // warnings do not fail the run
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  CHECK(summary["status"] == "completed");
  REQUIRE(summary["warnings"].contains("strain_above_budget"));
  REQUIRE(summary["warnings"].contains("penetration_above_budget"));
  CHECK(summary["monitors"]["max_internal_strain"].get<double>() > 1e-4);
  CHECK(summary["monitors"]["max_penetration_m"].get<double>() > 1e-4);
  CHECK(r.out.find("warning (strain_above_budget): max internal strain") != std::string::npos);
  check_no_nan(dir / "out");
}

TEST_CASE("extreme CLI: an explicit solver past its limit exits 1 as diverged, files finite",
          "[extremes][cli]") {
  TempDir dir;
  const Run r =
      pronk(dir, {"simulate",
                  std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/explicit_instability.json",
                  "--set", "/simulation/method=euler", "--out", dir / "out"});
  CHECK(r.code == 1);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  CHECK(summary["status"] == "diverged");
  CHECK(summary["reason"].get<std::string>().find("energy blow-up") != std::string::npos);
  check_no_nan(dir / "out");
}

TEST_CASE("extreme CLI: the small-angle formulation past 15 deg warns once", "[extremes][cli]") {
  TempDir dir;
  const Run r = pronk(
      dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case1_body_only.json",
            "--set", "/attitude=small_angle_euler123", "--set", "/initial/attitude_deg/0=20",
            "--out", dir / "out"});
  CHECK(r.code == 0);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  REQUIRE(summary["warnings"].size() == 1);
  CHECK(summary["warnings"]["small_angle_range_exceeded"].get<long>() >= 1);
  CHECK(r.out.find("warning: small_angle_range_exceeded") != std::string::npos);
  check_no_nan(dir / "out");
}
