// End-to-end journal integrity: every journal line carries a checksum, and
// --resume re-evaluates the last record; an edited, forged or old journal is
// refused (exit 2, naming the journal file and the line), a torn last line is
// still dropped and the study resumes to the uninterrupted run's bytes.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "optimize/journal.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/optimize/map/map_test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kStudy = std::string(PRONK_SOURCE_DIR) + "/studies/study1_body_only_gains.json";

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

/// Writes `lines` as the journal of a fresh output directory `dir`.
void plant(const TempDir& d, const std::string& dir, const std::string& text) {
  std::filesystem::create_directories(d / dir);
  write_file(d / (dir + "/journal.jsonl"), text);
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
    t.back() = ::pronk::optimize::sealed(rec).dump();
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

  // The last cell record, changed and sealed again: its re-computation differs.
  t = lines;
  size_t last_cell = 0;
  for (size_t i = 1; i < t.size(); ++i)
    if (json::parse(t[i])["task"] == "cell") last_cell = i;
  REQUIRE(last_cell > 0);
  rec = json::parse(t[last_cell]);
  rec.erase("checksum");
  rec["trials"][0][0][3] = rec["trials"][0][0][3].get<long>() + 1;  // one more stride
  t[last_cell] = ::pronk::optimize::sealed(rec).dump();
  plant(d, "f", joined(t));
  r = cli_support::pronk(d, {"map", "map.json", "--out", "f", "--resume", "-q"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             StartsWith("pronk: error: f/journal.jsonl: line " + std::to_string(last_cell + 1) +
                        ": expected the record its "
                        "re-computation gives"));
}
