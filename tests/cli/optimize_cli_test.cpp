// End-to-end tests of `pronk optimize` and `pronk reproduce`: bad input (exit
// 2 naming file and pointer), Ctrl-C keeping everything on disk, --resume
// finishing with the journal an uninterrupted run writes.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kStudies = std::string(PRONK_SOURCE_DIR) + "/studies/";

struct Dir {
  std::string path;
  Dir() {
    char t[] = "/tmp/pronk_opt_cli_XXXXXX";
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

/// Complete lines of a text.
long line_count(const std::string& text) {
  return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}

/// Freezes the child (SIGSTOP), counts the complete lines of its journal and, once there
/// are `from` to `below` - 1 of them, sends SIGINT while it is frozen (delivered on SIGCONT);
/// otherwise lets it run on and looks again. False (and its wait status) if it exited first.
bool interrupt_when(pid_t pid, const std::string& journal, long from, long below, int* status) {
  for (;;) {
    ::kill(pid, SIGSTOP);
    REQUIRE(::waitpid(pid, status, WUNTRACED) == pid);
    if (!WIFSTOPPED(*status)) return false;
    const long lines = line_count(slurp(journal));
    const bool now = lines >= from && lines < below;
    if (now) ::kill(pid, SIGINT);
    ::kill(pid, SIGCONT);
    if (now) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

// Runs pronk with arguments; returns the exit code, stderr in *err.
int pronk(const std::string& args, const std::string& dir, std::string* err = nullptr) {
  const std::string e = dir + "/stderr.txt";
  const int rc = std::system(
      (std::string(PRONK_EXE) + " " + args + " > " + dir + "/stdout.txt 2> " + e).c_str());
  if (err) *err = slurp(e);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace

TEST_CASE("optimize and reproduce reject bad input with exit 2", "[cli][optimize]") {
  Dir d;
  std::string err;
  CHECK(pronk("optimize " + d.path + "/missing.json", d.path, &err) == 2);
  CHECK(err.find("missing.json") != std::string::npos);
  json study = json::parse(slurp(kStudies + "study1_body_only_gains.json"));
  study["scene"] = kStudies + "scenes/case1_body_only.json";
  study["optimizer"]["algoritm"] = "LN_BOBYQA";
  { std::ofstream(d.path + "/bad.json") << study.dump(); }
  CHECK(pronk("optimize " + d.path + "/bad.json --out " + d.path + "/o", d.path, &err) == 2);
  CHECK(err.find("bad.json: /optimizer/algoritm: expected") != std::string::npos);
  CHECK_FALSE(fs::exists(d.path + "/o/journal.jsonl"));
  CHECK(pronk("optimize " + kStudies +
                  "study1_body_only_gains.json --set /parameters/0/lower=-1 --out " + d.path + "/o",
              d.path, &err) == 2);
  CHECK(err.find("/parameters/0/lower") != std::string::npos);
  CHECK(pronk("reproduce " + kStudies + "scenes/case1_body_only.json", d.path, &err) == 2);
  CHECK(err.find("/type: expected \"pronk_design\"") != std::string::npos);
  CHECK(pronk("optimize --threads 0 " + kStudies + "study1_body_only_gains.json", d.path) == 2);
}

TEST_CASE("Ctrl-C keeps everything on disk and --resume finishes the same study",
          "[cli][optimize][journal]") {
  Dir d;
  const std::string args = "optimize " + kStudies +
                           "study1_body_only_gains.json --threads 1 -q "
                           "--set /optimizer/max_evaluations=1000 --set /optimizer/xtol_rel=0 "
                           "--set /optimizer/ftol_rel=0 --out ";
  // Uninterrupted reference.
  REQUIRE(pronk(args + d.path + "/full", d.path) == 0);
  const std::string reference = slurp(d.path + "/full/journal.jsonl");
  const long reference_lines = line_count(reference);

  // Interrupted run: Ctrl-C once its journal holds a few records (so the handler is
  // installed), sent while the process is frozen, so when it arrives does not depend on
  // how fast the machine is or how the processes are scheduled.
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const std::string cmd = std::string(PRONK_EXE) + " " + args + d.path + "/cut > /dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  const bool interrupted =
      interrupt_when(pid, d.path + "/cut/journal.jsonl", 4, reference_lines - 1, &status);
  if (interrupted) REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  if (!interrupted) {
    // Only if the study ran its last ~1000 evaluations between two looks at its journal.
    WARN("the study finished before the interrupt could be sent");
    return;
  }
  CHECK(WEXITSTATUS(status) == 1);  // stopped
  const json design = json::parse(slurp(d.path + "/cut/design.json"));
  CHECK(design["optimizer"]["status"] == "stopped");
  const std::string partial = slurp(d.path + "/cut/journal.jsonl");
  CHECK(partial.size() < reference.size());
  CHECK(reference.compare(0, partial.size(), partial) == 0);  // a prefix of the full journal

  // Without --resume an existing journal is refused; with it the study completes identically.
  CHECK(pronk(args + d.path + "/cut", d.path) == 2);
  REQUIRE(pronk(args + d.path + "/cut --resume", d.path) == 0);
  CHECK(slurp(d.path + "/cut/journal.jsonl") == reference);
  CHECK(pronk("reproduce " + d.path + "/cut/design.json", d.path) == 0);
}

TEST_CASE("the committed study results reproduce, and study 2 meets its mission",
          "[cli][optimize][results]") {
  Dir d;
  const std::string results = std::string(PRONK_SOURCE_DIR) + "/results/";
  for (const char* study : {"study1_body_only_gains", "study2_legged_pulse_duty50"}) {
    INFO(study);
    CHECK(pronk("reproduce " + results + study + "/design.json", d.path) == 0);
  }
  // Study 2: >= 95 % of the 64 held-out disturbed trials stabilized at ~50 % duty.
  const json design = json::parse(slurp(results + "study2_legged_pulse_duty50/design.json"));
  const json& v = design["validation"];
  CHECK(v["scenarios"].get<int>() == 64);
  CHECK(v["metrics"]["stabilized"].get<double>() >= 0.95);
  CHECK(v["metrics"]["duty_mean"].get<double>() >= 0.45);
  CHECK(v["metrics"]["duty_mean"].get<double>() <= 0.5);
  // The starting design (seed-style gains) does not.
  CHECK(v["initial_metrics"]["stabilized"].get<double>() < 0.5);
}

TEST_CASE("optimize into a log prints progress lines with the time elapsed and left",
          "[cli][optimize][progress]") {
  // stderr is a file here, not a terminal: plain lines, the first and the last always (and
  // one every 30 s between), so what the log holds does not depend on the machine's speed.
  Dir d;
  std::string err;
  REQUIRE(pronk("optimize " + kStudies +
                    "study2_legged_pulse_duty50.json --set /optimizer/max_evaluations=6 " +
                    "--out " + d.path + "/o",
                d.path, &err) == 0);
  INFO(err);
  CHECK(err.find('\r') == std::string::npos);
  CHECK(err.find("study2_legged_pulse_duty50: evaluation 1/6, ") != std::string::npos);
  CHECK(err.find(" elapsed, about ") != std::string::npos);
  CHECK(err.find(" left, best feasible cost ") != std::string::npos);
  CHECK(err.find("study2_legged_pulse_duty50: evaluation 6/6, ") != std::string::npos);
  CHECK(err.find(" elapsed, done, best feasible cost ") != std::string::npos);
  CHECK(err.find("study2_legged_pulse_duty50: validating on 64 held-out trials") !=
        std::string::npos);
  // The validation counts its trial runs (64 trials x 2 designs), the first and the last.
  CHECK(err.find("study2_legged_pulse_duty50: validation trial runs 1/128, ") != std::string::npos);
  CHECK(err.find("study2_legged_pulse_duty50: validation trial runs 128/128, ") !=
        std::string::npos);
  CHECK(err.find("study2_legged_pulse_duty50: validated in ") != std::string::npos);
  // compare.svg plots every attitude angle, pitch and yaw beside roll (trajectory.csv's 8-10).
  const std::string gp = slurp(d.path + "/o/compare.gp");
  for (const char* plot : {"u 1:8 w l", "u 1:9 w l", "u 1:10 w l", "'Pitch'", "'Yaw'"}) {
    CHECK(gp.find(plot) != std::string::npos);
  }
  // -q: nothing.
  REQUIRE(pronk("optimize " + kStudies +
                    "study2_legged_pulse_duty50.json --set /optimizer/max_evaluations=6 " +
                    "-q --out " + d.path + "/q",
                d.path, &err) == 0);
  CHECK(err.empty());
}
