// End-to-end journal integrity: every journal line carries a checksum chained to the line
// before, and --resume re-evaluates the last record; an edited, forged or old journal is
// refused (exit 2, naming the journal file and the line), a torn last line is
// still dropped and the study resumes to the uninterrupted run's bytes. A line deleted,
// duplicated, swapped or inserted is refused naming the line, and so is a map record that
// contradicts the study or its neighbours; --resume --verify catches a forger who
// recomputed the chain; a map refuses to overwrite an interrupted journal; a second run on
// a locked --out is refused naming the holder; timings.csv keeps one line per journal
// record over a kill and a resume.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "optimize/journal.hpp"
#include "optimize/output_lock.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/optimize/map/map_test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kStudy = std::string(PRONK_SOURCE_DIR) + "/studies/study1_body_only_gains.json";
const std::string kStudy2 =
    std::string(PRONK_SOURCE_DIR) + "/studies/study2_legged_pulse_duty50.json";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

Run optimize(const TempDir& d, const std::string& out, bool resume) {
  std::vector<std::string> args = {
      "optimize", kStudy, "--threads", "1", "-q", "--set", "/optimizer/max_evaluations=12",
      "--out",    out};
  if (resume) args.push_back("--resume");
  return cli_support::pronk(d, args);
}

/// Writes `text` as the journal of a fresh output directory `dir`.
void plant(const TempDir& d, const std::string& dir, const std::string& text) {
  std::filesystem::create_directories(d / dir);
  write_file(d / (dir + "/journal.jsonl"), text);
}

std::string checksum_of(const std::string& line) {
  return json::parse(line).at("checksum").get<std::string>();
}

// Seals lines[i] for i >= from again, chained: what a forger who knows the format does.
void rechain(std::vector<std::string>& lines, size_t from) {
  std::string previous = checksum_of(lines[from - 1]);
  for (size_t i = from; i < lines.size(); ++i) {
    lines[i] = ::pronk::optimize::sealed(json::parse(lines[i]), previous).dump();
    previous = checksum_of(lines[i]);
  }
}

// Study 2 (60 evaluations, as in issue 34) into `out`.
Run study2(const TempDir& d, const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"optimize", kStudy2, "--threads",
                                   "2",        "--set", "/optimizer/max_evaluations=60",
                                   "--out",    out};
  args.insert(args.end(), extra.begin(), extra.end());
  return cli_support::pronk(d, args);
}

/// Writes `lines` as the journal of a fresh output directory `dir`.
void plant(const TempDir& d, const std::string& dir, const std::vector<std::string>& lines) {
  plant(d, dir, joined(lines));
}

}  // namespace

TEST_CASE("study journals: edits, forgeries and old journals are refused on --resume",
          "[cli][optimize][journal]") {
  TempDir d("journal");
  REQUIRE(optimize(d, "full", false).code == 0);
  const std::string reference = slurp(d / "full/journal.jsonl");
  const std::vector<std::string> lines = lines_of(reference);
  REQUIRE(lines.size() >= 6);
  for (const std::string& l : lines) CHECK(json::parse(l).contains("checksum"));

  SECTION("a mid-file record with its cost edited (still valid JSON): exit 2 with the line") {
    std::vector<std::string> t = lines;
    json rec = json::parse(t[4]);
    rec["cost"] = 999;
    t[4] = rec.dump();
    plant(d, "t", joined(t));
    const Run r = optimize(d, "t", true);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: line 5 /checksum: expected "
                                 "checksum "));
    CHECK(slurp(d / "t/journal.jsonl") == joined(t));  // nothing appended
  }
  SECTION("a forged last record (checksum recomputed) differs from its re-evaluation") {
    std::vector<std::string> t = lines;
    json rec = json::parse(t.back());
    rec["cost"] = std::nextafter(rec["cost"].get<double>(), 1e300);
    const std::string before = json::parse(t[t.size() - 2]).at("checksum").get<std::string>();
    t.back() = ::pronk::optimize::sealed(rec, before).dump();
    plant(d, "f", joined(t));
    const Run r = optimize(d, "f", true);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: f/journal.jsonl: line " + std::to_string(t.size()) +
                                 " /cost: expected the value its re-evaluation gives"));
  }
  SECTION("a journal without checksums (an older pronk) is refused at line 1") {
    std::vector<std::string> t = lines;
    for (std::string& l : t) {
      json rec = json::parse(l);
      rec.erase("checksum");
      l = rec.dump();
    }
    plant(d, "o", joined(t));
    const Run r = optimize(d, "o", true);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: o/journal.jsonl: line 1 /checksum: expected a "
                                 "record with its checksum"));
  }
  SECTION("a journal of half a header (killed at once) resumes from scratch") {
    plant(d, "h", lines[0].substr(0, lines[0].size() / 2));
    CHECK(optimize(d, "h", true).code == 0);
    CHECK(slurp(d / "h/journal.jsonl") == reference);
  }
  SECTION("a torn last line is still dropped and the study resumes to the same bytes") {
    std::vector<std::string> t(lines.begin(), lines.begin() + 5);
    const std::string half = lines[5].substr(0, lines[5].size() / 2);
    plant(d, "c", joined(t) + half);
    const Run r = optimize(d, "c", true);
    CHECK(r.code == 0);
    CHECK(slurp(d / "c/journal.jsonl") == reference);
  }
}

TEST_CASE("map journals: an edited cell or a forged last cell is refused on --resume",
          "[cli][map][journal]") {
  TempDir d("journal");
  write_file(d / "map.json", ::pronk::test::tiny_map_document(3, 2, 4.0).dump());
  REQUIRE(cli_support::pronk(d, {"map", "map.json", "--out", "m", "-q"}).code == 0);
  const std::vector<std::string> lines = lines_of(slurp(d / "m/journal.jsonl"));
  REQUIRE(lines.size() >= 4);
  std::vector<std::string> t = lines;
  json rec = json::parse(t[2]);
  rec["seconds_edited"] = 1;
  t[2] = rec.dump();
  plant(d, "e", joined(t));
  Run r = cli_support::pronk(d, {"map", "map.json", "--out", "e", "--resume", "-q"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: e/journal.jsonl: line 3 /checksum: expected"));

  // The last cell record, changed consistently and sealed again with the chain recomputed
  // from there: its re-computation differs.
  t = lines;
  size_t last_cell = 0;
  for (size_t i = 1; i < t.size(); ++i)
    if (json::parse(t[i])["task"] == "cell") last_cell = i;
  REQUIRE(last_cell > 0);
  rec = json::parse(t[last_cell]);
  rec["trials"][0][0][4] = rec["trials"][0][0][4].get<double>() + 1e-3;  // another duty
  std::string previous = json::parse(t[last_cell - 1]).at("checksum").get<std::string>();
  for (size_t i = last_cell; i < t.size(); ++i) {
    t[i] = ::pronk::optimize::sealed(i == last_cell ? rec : json::parse(t[i]), previous).dump();
    previous = json::parse(t[i]).at("checksum").get<std::string>();
  }
  plant(d, "f", joined(t));
  r = cli_support::pronk(d, {"map", "map.json", "--out", "f", "--resume", "-q"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             StartsWith("pronk: error: f/journal.jsonl: line " + std::to_string(last_cell + 1) +
                        ": expected the record its "
                        "re-computation gives"));
}

TEST_CASE("study journals: a deleted, duplicated, swapped or inserted line is refused",
          "[cli][optimize][journal]") {
  TempDir d("journal");
  REQUIRE(study2(d, "full", {"-q"}).code == 0);
  const std::vector<std::string> lines = lines_of(slurp(d / "full/journal.jsonl"));
  REQUIRE(lines.size() == 61);  // header + evaluations 0..59
  auto refused_at = [&](const std::vector<std::string>& t, const std::string& where) {
    plant(d, "t", t);
    const Run r = study2(d, "t", {"-q", "--resume"});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: " + where + ": expected "));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(slurp(d / "t/journal.jsonl") == joined(t));  // nothing appended or rewritten
    std::filesystem::remove_all(d / "t");
  };
  std::vector<std::string> t = lines;
  t.erase(t.begin() + 29);  // line 30 deleted
  refused_at(t, "line 30 /checksum");
  t = lines;
  t.insert(t.begin() + 29, lines[29]);  // line 30 twice
  refused_at(t, "line 31 /checksum");
  t = lines;
  std::swap(t[29], t[30]);  // lines 30 and 31 swapped
  refused_at(t, "line 30 /checksum");
  t = lines;
  json forged = json::parse(lines[29]);
  forged["cost"] = -1.0;
  t.insert(t.begin() + 29, ::pronk::optimize::sealed(forged, checksum_of(lines[28])).dump());
  refused_at(t, "line 31 /checksum");  // inserted before line 30, which no longer chains
  t = lines;
  t[29] = ::pronk::optimize::sealed(forged, checksum_of(lines[28])).dump();  // one line re-sealed
  refused_at(t, "line 31 /checksum");
  // With the chain recomputed, the indices still give a deletion away ...
  t = lines;
  t.erase(t.begin() + 29);
  rechain(t, 29);
  refused_at(t, "line 30 /index");
  // ... but not an edited value: only evaluating the record again does.
  t = lines;
  t[29] = forged.dump();
  rechain(t, 29);
  plant(d, "v", t);
  const Run r = study2(d, "v", {"-q", "--resume", "--verify"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: v/journal.jsonl: line 30 /cost: expected the value "
                               "its re-evaluation gives"));
}

TEST_CASE("resume with --verify evaluates every record, or a seeded sample, again",
          "[cli][optimize][journal]") {
  TempDir d("journal");
  REQUIRE(study2(d, "full", {"-q"}).code == 0);
  const std::string reference = slurp(d / "full/journal.jsonl");
  const std::vector<std::string> lines = lines_of(reference);
  plant(d, "a", std::vector<std::string>(lines.begin(), lines.begin() + 40));
  Run r = study2(d, "a", {"--resume", "--verify"});
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("(39 replayed, 39 of them verified)"));
  CHECK(slurp(d / "a/journal.jsonl") == reference);
  plant(d, "s", std::vector<std::string>(lines.begin(), lines.begin() + 40));
  r = study2(d, "s", {"--resume", "--verify", "5", "--verify-seed", "7"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("(39 replayed, 5 of them verified)"));
  CHECK(slurp(d / "s/journal.jsonl") == reference);
  r = study2(d, "n", {"--verify"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: --verify: /: expected --resume with it"));
}

TEST_CASE("map journals: records that contradict the study or their neighbours are refused",
          "[cli][map][journal]") {
  TempDir d("journal");
  // One row of three duty cells whose boundary is bisected (as in map_engine_test).
  json doc = ::pronk::test::tiny_map_document(3, 2, 8.0);
  doc["axes"] = {{{"kind", "duty_cycle"}, {"range", {0.2, 0.4}}, {"count", 3}}};
  doc["boundary"] = {{"resolution", 0.004}};
  write_file(d / "map.json", doc.dump());
  REQUIRE(cli_support::pronk(d, {"map", "map.json", "--out", "m", "-q"}).code == 0);
  const std::vector<std::string> lines = lines_of(slurp(d / "m/journal.jsonl"));
  size_t boundary = 0;
  for (size_t i = 1; i < lines.size(); ++i)
    if (json::parse(lines[i])["task"] == "boundary") boundary = i;
  REQUIRE(boundary > 0);  // a row with a bisected boundary
  auto forged = [&](size_t i, const std::function<void(json&)>& edit) {
    std::vector<std::string> t = lines;
    json rec = json::parse(t[i]);
    edit(rec);
    t[i] = rec.dump();
    rechain(t, i);
    return t;
  };
  auto resume = [&](const std::vector<std::string>& t, std::vector<std::string> extra = {}) {
    plant(d, "t", t);
    std::vector<std::string> args = {"map", "map.json", "--out", "t", "--resume", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Run r = cli_support::pronk(d, args);
    std::filesystem::remove_all(d / "t");
    return r;
  };
  // A middle cell missing a trial, or with a trial's "stabilized" against the study's rule.
  Run r = resume(forged(2, [](json& c) { c["trials"][0].erase(1); }));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: line 3 /trials/0: expected 2 "
                               "trials (the study's trial count), found 1"));
  r = resume(forged(2, [](json& c) { c["trials"][0][1][1] = !c["trials"][0][1][1].get<bool>(); }));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: line 3 /trials/0/1: expected a "
                               "trial as the simulator and the study's \"stabilized\" rule give"));
  // A boundary outside its bracket, and one inside it that no bisection reaches.
  const size_t b = boundary;
  const std::string line_b = "line " + std::to_string(b + 1) + " /good: expected a bracket";
  r = resume(forged(b, [](json& j) { j["boundary"] = 0.3; }));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: " + line_b));
  r = resume(forged(b, [](json& j) { j["boundary"] = j["good"] = 0.5; }));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: " + line_b));
  r = resume(forged(b, [](json& j) {
    const double g = j["good"].get<double>(), bad = j["bad"].get<double>();
    j["boundary"] = j["good"] = g + 0.25 * (bad - g);
  }));
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: " + line_b));
  // A consistent forgery (a trial's duty) passes every check but computing it again.
  const std::vector<std::string> quiet_forgery =
      forged(2, [](json& c) { c["trials"][0][0][4] = c["trials"][0][0][4].get<double>() + 1e-3; });
  r = resume(quiet_forgery, {"--verify"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: line 3: expected the record its "
                               "re-computation gives"));
  // A deleted line is refused at the chain.
  std::vector<std::string> t = lines;
  t.erase(t.begin() + 2);
  r = resume(t);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: t/journal.jsonl: line 3 /checksum"));
}

TEST_CASE("map without --resume refuses an interrupted journal and keeps it",
          "[cli][map][journal]") {
  TempDir d("journal");
  write_file(d / "map.json", ::pronk::test::tiny_map_document(3, 2, 4.0).dump());
  REQUIRE(cli_support::pronk(d, {"map", "map.json", "--out", "m", "-q"}).code == 0);
  const std::vector<std::string> lines = lines_of(slurp(d / "m/journal.jsonl"));
  const std::vector<std::string> cut(lines.begin(), lines.begin() + 3);
  plant(d, "i", cut);
  const Run r = cli_support::pronk(d, {"map", "map.json", "--out", "i", "-q"});
  CHECK(r.code == 2);
  CHECK(r.err ==
        "pronk: error: i/journal.jsonl: /: expected no journal (pass --resume to continue it, or "
        "choose another --out), found the journal of an earlier run\n");
  CHECK(slurp(d / "i/journal.jsonl") == joined(cut));
  REQUIRE(cli_support::pronk(d, {"map", "map.json", "--out", "i", "-q", "--resume"}).code == 0);
  CHECK(slurp(d / "i/journal.jsonl") == joined(lines));
}

TEST_CASE("a second run on a locked output directory is refused, naming the holder",
          "[cli][journal][lock]") {
  TempDir d("journal");
  write_file(d / "map.json", ::pronk::test::tiny_map_document(3, 2, 4.0).dump());
  json staged = json::parse(slurp(kStudy));
  staged["scene"] = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case1_body_only.json";
  staged["stages"] = {{{"name", "one"}, {"model", "impulse"}}};
  write_file(d / "staged.json", staged.dump());
  std::filesystem::create_directories(d / "busy");
  const ::pronk::optimize::OutputLock held(d / "busy", "a test");
  const std::string holder =
      "found pid " + std::to_string(::getpid()) + " (a test) holding its lock\n";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"optimize", kStudy, "--out", "busy", "-q"},
        std::vector<std::string>{"optimize", "staged.json", "--out", "busy", "-q"},
        std::vector<std::string>{"map", "map.json", "--out", "busy", "-q"}}) {
    INFO(args[1]);
    const Run r = cli_support::pronk(d, args);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: busy/pronk.lock: /: expected an output directory "
                                 "no other run is writing to"));
    CHECK_THAT(r.err, Catch::Matchers::EndsWith(holder));
    CHECK_FALSE(std::filesystem::exists(d / "busy/journal.jsonl"));
  }
}

TEST_CASE("timings.csv has one line per journal record after a kill and --resume",
          "[cli][optimize][journal]") {
  TempDir d("journal");
  const std::vector<std::string> args = {
      "optimize", kStudy, "--threads", "1", "-q", "--set", "/optimizer/max_evaluations=12",
      "--out"};
  auto run = [&](const std::string& out, bool resume) {
    std::vector<std::string> a = args;
    a.push_back(out);
    if (resume) a.push_back("--resume");
    return cli_support::pronk(d, a);
  };
  REQUIRE(run("full", false).code == 0);
  const std::vector<std::string> journal = lines_of(slurp(d / "full/journal.jsonl"));
  const std::vector<std::string> timings = lines_of(slurp(d / "full/timings.csv"));
  REQUIRE(journal.size() == 13);
  REQUIRE(timings.size() == 13);
  // Killed after record 7 reached the journal and before its timings line (the order of an
  // older pronk), or after a timings line whose record never reached the journal.
  for (const bool spare : {false, true}) {
    INFO((spare ? "a spare timings line" : "a missing timings line"));
    const std::string out = spare ? "spare" : "missing";
    plant(d, out, std::vector<std::string>(journal.begin(), journal.begin() + 9));  // 0..7
    write_file(
        d / (out + "/timings.csv"),
        joined(std::vector<std::string>(timings.begin(), timings.begin() + (spare ? 10 : 8))));
    REQUIRE(run(out, true).code == 0);
    const std::vector<std::string> now = lines_of(slurp(d / (out + "/timings.csv")));
    REQUIRE(now.size() == 13);
    CHECK(now[0] == timings[0]);
    for (long i = 0; i < 12; ++i) {
      INFO("index " << i);
      const std::string& l = now[static_cast<size_t>(i) + 1];
      CHECK(l.rfind(std::to_string(i) + ",", 0) == 0);
      const json rec = json::parse(journal[static_cast<size_t>(i) + 1]);
      const std::string counts = "," + rec["simulations"].dump() + "," + rec["strides"].dump();
      CHECK(l.size() > counts.size());
      CHECK(l.compare(l.size() - counts.size(), counts.size(), counts) == 0);
      if (i == 7 && !spare) CHECK(l == "7,," + counts);  // its times were lost
    }
  }
}
