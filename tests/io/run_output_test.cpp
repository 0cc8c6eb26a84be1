// Tests of io/write/run_output.hpp and io/write/atomic_file.hpp: non-finite numbers
// never reach a JSON output, atomic writes replace files and leave no
// temporaries, and the CSV outputs are rectangular with exact values.
#include "io/write/run_output.hpp"

#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "sim/reduced/simulator.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;
namespace io = pronk::io;
namespace reduced = pronk::reduced;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A fresh directory under /tmp, removed at scope exit.
struct ScratchDir {
  std::string path;
  ScratchDir() {
    char tmpl[] = "/tmp/pronk_io_test_XXXXXX";
    const char* p = ::mkdtemp(tmpl);
    REQUIRE(p != nullptr);
    path = p;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// The message of the std::logic_error dump_checked throws for j.
std::string dump_error(const json& j) {
  try {
    io::dump_checked(j);
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

long columns(const std::string& line) { return std::count(line.begin(), line.end(), ',') + 1; }

/// Every row has the header's column count; returns the number of data rows.
size_t check_rectangular(const std::string& csv, long expected_columns) {
  const std::vector<std::string> lines = lines_of(csv);
  REQUIRE_FALSE(lines.empty());
  CHECK(columns(lines[0]) == expected_columns);
  for (size_t i = 1; i < lines.size(); ++i) {
    INFO("line " << i << ": " << lines[i]);
    REQUIRE(columns(lines[i]) == expected_columns);
  }
  CHECK(csv.back() == '\n');
  return lines.size() - 1;
}

pronk::scene::Scene short_scene(const std::string& file, double duration) {
  return io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + file,
                        {"/simulation/duration=" + std::to_string(duration)});
}

}  // namespace

TEST_CASE("dump_checked rejects non-finite numbers naming their pointer", "[io][output]") {
  CHECK(dump_error({{"a", {{"b", {1.0, kNaN}}}}}) == "non-finite number in output at /a/b/1");
  CHECK(dump_error({{"x", kInf}}) == "non-finite number in output at /x");
  CHECK(dump_error(json::array({0.5, json::array({-kInf})})) ==
        "non-finite number in output at /1/0");
  CHECK(dump_error(kNaN) == "non-finite number in output at ");
  // Finite documents are written in full, indented, with a final newline.
  const json ok = {{"a", {1, 2.5, -1e300}}, {"b", nullptr}, {"s", "nan"}};
  CHECK(io::dump_checked(ok) == ok.dump(2) + "\n");
  CHECK(json::parse(io::dump_checked(ok)) == ok);
}

TEST_CASE("a summary with a non-finite metric cannot be written", "[io][output]") {
  const auto scene = short_scene("case1_body_only.json", 0.5);
  reduced::RunResult run;
  run.reason = "reached t = 0.5 s";
  run.t_end = 0.5;
  reduced::RunMetrics m;
  m.strides = 1;
  const json good = io::run_summary_json(scene, run, m);
  CHECK(good["status"] == "completed");
  CHECK(good["scene"] == "case1_body_only");
  CHECK(good["metrics"]["strides"] == 1);
  CHECK(good["solver"]["rtol"] == 1e-9);
  CHECK_NOTHROW(io::dump_checked(good));
  m.final_x_error = kNaN;
  CHECK(dump_error(io::run_summary_json(scene, run, m)) ==
        "non-finite number in output at /metrics/final_x_error_m");
  m.final_x_error = 0.0;
  run.monitors.max_flight_energy_drift = kInf;
  CHECK(dump_error(io::run_summary_json(scene, run, m)) ==
        "non-finite number in output at /monitors/max_flight_energy_drift");
}

TEST_CASE("write_file_atomic replaces content and leaves no temporary file", "[io][atomic]") {
  ScratchDir dir;
  const std::string path = dir.path + "/out.txt";
  io::write_file_atomic(path, "first version, rather long\n");
  CHECK(slurp(path) == "first version, rather long\n");
  io::write_file_atomic(path, "second\n");
  CHECK(slurp(path) == "second\n");  // replaced, not overwritten in place
  const std::string binary("a\0b\nc", 5);
  io::write_file_atomic(path, binary);
  CHECK(slurp(path) == binary);
  io::write_file_atomic(dir.path + "/empty.txt", "");
  CHECK(fs::file_size(dir.path + "/empty.txt") == 0);
  CHECK(names_in(dir.path) == std::vector<std::string>{"empty.txt", "out.txt"});

  // A large payload arrives complete.
  const std::string big(3 << 20, 'x');
  io::write_file_atomic(path, big);
  CHECK(slurp(path) == big);

  // Failure: the directory does not exist; the error names the path.
  const std::string bad = dir.path + "/missing/out.txt";
  try {
    io::write_file_atomic(bad, "x");
    FAIL("write_file_atomic into a missing directory did not throw");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Contains(dir.path + "/missing/out.txt"));
  }
  // Failure at rename (the target is a non-empty directory): the temporary is removed.
  fs::create_directories(dir.path + "/blocker/inner");
  CHECK_THROWS_AS(io::write_file_atomic(dir.path + "/blocker", "x"), std::runtime_error);
  CHECK(names_in(dir.path) == std::vector<std::string>{"blocker", "empty.txt", "out.txt"});
  CHECK(slurp(path) == big);
}

TEST_CASE("make_directories creates parents and reports a path that cannot be one",
          "[io][atomic]") {
  ScratchDir dir;
  io::make_directories(dir.path + "/a/b/c");
  CHECK(fs::is_directory(dir.path + "/a/b/c"));
  io::make_directories(dir.path + "/a/b/c");  // existing: fine
  io::write_file_atomic(dir.path + "/file", "x");
  try {
    io::make_directories(dir.path + "/file/sub");
    FAIL("make_directories below a regular file did not throw");
  } catch (const io::InputError& e) {  // bad input: a part of the path is a file
    CHECK(e.file() == dir.path + "/file/sub");
    CHECK(e.found() == "\"" + dir.path + "/file\", a part of the path that is a file");
  }
}

TEST_CASE("CSV rows have exactly the header's columns and exact values", "[io][output]") {
  reduced::RunResult run;
  reduced::Sample s;
  s.t = 0.5;
  s.position = {1, 2, 3};
  s.velocity = {-1, 0.25, 0};
  s.euler123 = {M_PI / 2, 0, -M_PI};
  s.omega = {0, 0, 1e-20};
  s.setpoint = {0.1, 0, 0};
  s.stance = true;
  s.leg_force_world = {0, 0, 14.715};
  run.trajectory = {s, s};
  run.trajectory[1].stance = false;
  run.trajectory[1].t = 0.505;

  const std::string traj = io::trajectory_csv(run);
  CHECK(check_rectangular(traj, 19) == 2);
  const auto lines = lines_of(traj);
  CHECK(lines[0] == "t,x,y,z,vx,vy,vz,roll_deg,pitch_deg,yaw_deg,wx,wy,wz,x_d,y_d,stance,Fx,Fy,Fz");
  CHECK(lines[1] ==
        "0.5,1,2,3,-1,0.25,0,90,0,-180,0,0,9.9999999999999995e-21,0.10000000000000001,0,1,0,0,"
        "14.715");
  CHECK(lines[2].substr(0, 22) == "0.505,1,2,3,-1,0.25,0,");
  CHECK(lines[2].find(",0,0,0,14.715") != std::string::npos);  // stance 0
  // %.17g: every value reads back to the same double.
  CHECK(std::stod("0.10000000000000001") == 0.1);

  reduced::StrideRecord r;
  r.index = 3;
  r.t_touchdown = 1.25;
  r.has_apex = false;
  r.apex_height = 0.7;  // ignored without an apex
  r.active_legs = 4;
  r.allocation = pronk::control::AllocationStatus::kOk;
  run.strides = {r};
  const std::string strides = io::strides_csv(run);
  CHECK(check_rectangular(strides, 33) == 1);
  const auto sl = lines_of(strides);
  CHECK(sl[1].substr(0, 7) == "3,1.25,");
  CHECK(sl[1].substr(sl[1].size() - 4) == ",4,1");
  const std::vector<std::string> cells = [&] {
    std::vector<std::string> c;
    std::istringstream in(sl[1]);
    std::string cell;
    while (std::getline(in, cell, ',')) c.push_back(cell);
    return c;
  }();
  REQUIRE(cells.size() == 33);
  CHECK(cells[13] == "0");  // apex_height column without an apex

  // No strides, no samples: the header alone.
  reduced::RunResult empty;
  CHECK(check_rectangular(io::trajectory_csv(empty), 19) == 0);
  CHECK(check_rectangular(io::strides_csv(empty), 33) == 0);
}

TEST_CASE("CSV numbers are printf's %.17g, bit for bit", "[io][output]") {
  // table_csv and exact_number format with std::to_chars; the files must stay what
  // printf wrote: the extremes, signed zeros, subnormals, non-finite values, and a sweep.
  std::vector<double> values = {0.0,
                                -0.0,
                                0.1,
                                1.0 / 3.0,
                                1e-20,
                                14.715,
                                1e16,
                                1e17,
                                -1e300,
                                5e-324,
                                1e-310,
                                kNaN,
                                -kNaN,
                                kInf,
                                -kInf,
                                std::numeric_limits<double>::max(),
                                2.2250738585072014e-308};
  for (int e = -30; e <= 30; ++e) {
    for (double m : {1.0, 1.5, 2.0 / 3.0, 9.999999999999999, 123456.789}) {
      values.push_back(std::ldexp(m, e));
      values.push_back(-m * std::pow(10.0, e));
    }
  }
  io::Table t;
  t.columns = {"v"};
  std::string expected = "v\n";
  for (double v : values) {
    t.add_row({v});
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    INFO(buf);
    CHECK(io::exact_number(v) == buf);
    expected += std::string(buf) + "\n";
  }
  CHECK(io::table_csv(t) == expected);
}

TEST_CASE("CSV and JSON outputs of a simulated run", "[io][output]") {
  const auto scene = short_scene("case2_legged_impulse.json", 1.0);
  const reduced::RunResult run = reduced::simulate(scene);
  REQUIRE(run.status == reduced::RunStatus::kCompleted);
  const reduced::RunMetrics m = reduced::compute_metrics(scene, run);

  CHECK(check_rectangular(io::trajectory_csv(run), 19) == run.trajectory.size());
  CHECK(run.trajectory.size() == 201);
  const size_t n_strides = check_rectangular(io::strides_csv(run), 33);
  CHECK(n_strides == run.strides.size());
  CHECK(n_strides >= 2);

  ScratchDir dir;
  const std::string out = dir.path + "/nested/run";
  io::FigureBatch figures;
  io::write_run_outputs(out, scene, run, m, figures);
  figures.finish();
  for (const std::string& f : names_in(out)) {
    INFO(f);
    CHECK(f.find(".tmp") == std::string::npos);
  }
  CHECK(slurp(out + "/trajectory.csv") == io::trajectory_csv(run));
  CHECK(slurp(out + "/strides.csv") == io::strides_csv(run));
  const json summary = json::parse(slurp(out + "/summary.json"));
  CHECK(summary["metrics"]["strides"] == m.strides);
  CHECK(summary["t_end"] == 1.0);
  const json resolved = json::parse(slurp(out + "/scene.resolved.json"));
  CHECK(resolved == io::scene_to_json(scene));
  CHECK(fs::is_regular_file(out + "/motion.gp"));
  CHECK(fs::is_regular_file(out + "/strides.gp"));
  CHECK_FALSE(fs::exists(out + "/leg_force.gp"));  // impulse model: no leg force figure
}
