// `mpirun -np 2 pronk optimize`: the evaluations' scenario runs spread over the
// ranks give the threaded run's journal byte for byte (derivative-free NLopt,
// Ipopt's finite-difference batches, a pagmo population, a staged study), --resume
// replays under MPI, and bad input is reported once by rank 0.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli/cli_support.hpp"

#ifdef PRONK_MPIEXEC

using nlohmann::json;

namespace {

const std::string kStudy1 = std::string(PRONK_SOURCE_DIR) + "/studies/study1_body_only_gains.json";

/// Runs `pronk ARGS` under `mpirun -np 2` (as root, on 2 cores; leak checks off
/// for the ranks only, as in the map test: OpenMPI leaks in its own start-up).
cli_support::Run mpi_pronk(const cli_support::TempDir& d, const std::string& args) {
  std::string cmd = "cd " + cli_support::quote(d.path) + " && ASAN_OPTIONS=detect_leaks=0 ";
  cmd += PRONK_MPIEXEC;
  cmd += " -x ASAN_OPTIONS --allow-run-as-root --oversubscribe -np 2 ";
  cmd += cli_support::quote(PRONK_EXE) + " " + args;
  cmd += " >" + cli_support::quote(d / ".stdout") + " 2>" + cli_support::quote(d / ".stderr");
  const int status = std::system(cmd.c_str());
  cli_support::Run r;
  if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.out = cli_support::slurp(d / ".stdout");
  r.err = cli_support::slurp(d / ".stderr");
  return r;
}

/// Study 1 made small: `evaluations` evaluations of 6 scenarios of 1.5 s.
json small_study1(long evaluations) {
  json doc = json::parse(cli_support::slurp(kStudy1));
  doc["scene"] = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case1_body_only.json";
  doc["scenarios"]["duration"] = 1.5;
  doc["scenarios"]["random"]["count"] = 6;
  doc["optimizer"]["max_evaluations"] = evaluations;
  return doc;
}

/// The same study in one process on 2 threads and on 2 MPI ranks: the same files.
void check_same_as_threads(const cli_support::TempDir& d, const json& study,
                           const std::vector<std::string>& files) {
  cli_support::write_file(d / "s.json", study.dump());
  const auto threads =
      cli_support::pronk(d, {"optimize", "s.json", "-q", "--threads", "2", "--out", d / "threads"});
  INFO(threads.err);
  REQUIRE(threads.code == 0);
  const auto mpi = mpi_pronk(d, "optimize s.json --out " + cli_support::quote(d / "mpi"));
  INFO(mpi.err);
  REQUIRE(mpi.code == 0);
  CHECK(mpi.out.find("2 MPI ranks") != std::string::npos);
  for (const auto& f : files) {
    INFO(f);
    const std::string a = cli_support::slurp(d / ("threads/" + f));
    CHECK(!a.empty());
    CHECK(a == cli_support::slurp(d / ("mpi/" + f)));
  }
}

}  // namespace

TEST_CASE("mpirun -np 2 pronk optimize writes the threaded run's journal", "[cli][optimize][mpi]") {
  cli_support::TempDir d("optimize_mpi");
  check_same_as_threads(d, small_study1(12), {"journal.jsonl", "history.csv"});
  // The design's numbers too (its run record names the workers, which differ).
  const json a = json::parse(cli_support::slurp(d / "threads/design.json"));
  const json b = json::parse(cli_support::slurp(d / "mpi/design.json"));
  for (const char* key : {"unit", "parameters", "cost", "metrics", "constraints", "trials"}) {
    INFO(key);
    CHECK(a.at(key) == b.at(key));
  }
  // The perturbation run's evaluations went over the ranks too: the same tolerances.
  CHECK(a.at("reproduction").at("tolerance") == b.at("reproduction").at("tolerance"));

  // --resume under MPI replays the finished journal and rewrites nothing.
  const std::string before = cli_support::slurp(d / "mpi/journal.jsonl");
  const auto resumed =
      mpi_pronk(d, "optimize s.json -q --resume --out " + cli_support::quote(d / "mpi"));
  INFO(resumed.err);
  CHECK(resumed.code == 0);
  CHECK(cli_support::slurp(d / "mpi/journal.jsonl") == before);
}

TEST_CASE("mpirun -np 2 pronk optimize: Ipopt's finite-difference batches over the ranks",
          "[cli][optimize][mpi]") {
  cli_support::TempDir d("optimize_mpi_ipopt");
  json study = small_study1(30);
  study["parameters"] = json::array({study["parameters"][0], study["parameters"][2]});
  study["optimizer"] = {{"library", "ipopt"}, {"max_evaluations", 30}};
  check_same_as_threads(d, study, {"journal.jsonl", "history.csv"});
}

TEST_CASE("mpirun -np 2 pronk optimize: a pagmo population over the ranks",
          "[cli][optimize][mpi][pagmo]") {
  cli_support::TempDir d("optimize_mpi_pagmo");
  json study = small_study1(30);
  study["optimizer"] = {{"library", "pagmo"},
                        {"algorithm", "cmaes"},
                        {"max_evaluations", 30},
                        {"options", {{"population", 10}}}};
  check_same_as_threads(d, study, {"journal.jsonl", "history.csv"});
}

TEST_CASE("mpirun -np 2 pronk optimize: a staged study's stages over the ranks",
          "[cli][optimize][mpi]") {
  cli_support::TempDir d("optimize_mpi_staged");
  json study = small_study1(6);
  study["stages"] = json::array(
      {{{"name", "first"},
        {"model", "impulse"},
        {"optimizer", {{"library", "nlopt"}, {"algorithm", "LN_COBYLA"}, {"max_evaluations", 5}}}},
       {{"name", "second"},
        {"model", "impulse"},
        {"optimizer",
         {{"library", "nlopt"}, {"algorithm", "LN_BOBYQA"}, {"max_evaluations", 5}}}}});
  check_same_as_threads(d, study,
                        {"stages/1_first/journal.jsonl", "stages/2_second/journal.jsonl"});
}

TEST_CASE("mpirun -np 2 pronk optimize: bad input is reported once, every rank exits",
          "[cli][optimize][mpi]") {
  cli_support::TempDir d("optimize_mpi_bad");
  cli_support::write_file(d / "s.json", small_study1(3).dump());
  const auto r = mpi_pronk(d, "optimize s.json --set /optimizer/max_evalutions=3");
  CHECK(r.code == 2);
  const size_t first = r.err.find("pronk: error: ");
  REQUIRE(first != std::string::npos);
  CHECK(r.err.find("max_evalutions") != std::string::npos);
  CHECK(r.err.find("pronk: error: ", first + 1) == std::string::npos);
}

#endif
