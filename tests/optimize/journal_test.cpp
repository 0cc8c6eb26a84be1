// The journal format: chained checksums (a deleted, duplicated, moved, inserted or edited
// line is refused, naming the line), index continuity (which also catches a forger who
// re-chains after deleting a line), format-1 journals read and migrated on append, torn
// tails cut, and the seeded verification sample.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/load/input_error.hpp"
#include "optimize/journal.hpp"

using nlohmann::json;
using pronk::io::InputError;
using namespace pronk::optimize;  // NOLINT(google-build-using-namespace): test code

namespace {

json header() { return {{"type", "header"}, {"study_hash", "h"}}; }

json record(long index, double cost) {
  return {{"type", "evaluation"},        {"index", index}, {"purpose", "objective"},
          {"x", {0.5, 0.25 * index}},    {"ok", true},     {"cost", cost},
          {"constraints", json::array()}};
}

// The lines of a journal of `n` records as JournalWriter writes them (format 2).
std::vector<std::string> written_lines(const std::string& dir, long n) {
  const std::string path = dir + "/w.jsonl";
  {
    JournalWriter w(path, header(), "");
    for (long i = 0; i < n; ++i) w.append(record(i, 1.0 + i));
  }
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

InputError error_of(const std::vector<std::string>& lines) {
  try {
    (void)parse_journal(joined(lines), "j.jsonl");
  } catch (const InputError& e) {
    return e;
  }
  FAIL("the journal was accepted");
  return InputError("", "", "", "");
}

// Re-seals every line from `from` (0-based) on, chained: what a forger who knows the format does.
void rechain(std::vector<std::string>& lines, size_t from) {
  std::string previous = json::parse(lines[from - 1]).at("checksum").get<std::string>();
  for (size_t i = from; i < lines.size(); ++i) {
    json j = sealed(json::parse(lines[i]), previous);
    previous = j.at("checksum").get<std::string>();
    lines[i] = j.dump();
  }
}

struct TempDir {
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "pronk_journal_XXXXXX").string();
    REQUIRE(::mkdtemp(t.data()) != nullptr);
    path = t;
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string path;
};

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("chained journals refuse deleted, duplicated, moved, inserted and edited lines",
          "[optimize][journal]") {
  TempDir d;
  const std::vector<std::string> lines = written_lines(d.path, 6);  // header + records 0..5
  REQUIRE(lines.size() == 7);
  CHECK(json::parse(lines[0]).at("format") == kJournalFormat);
  const JournalContents ok = parse_journal(joined(lines), "j.jsonl");
  REQUIRE(ok.records.size() == 6);
  CHECK(ok.end.last_checksum == json::parse(lines[6]).at("checksum"));
  // The chain: each checksum is FNV-1a of the previous checksum and the content.
  CHECK(json::parse(lines[3]).at("checksum") ==
        record_checksum(json::parse(lines[3]), json::parse(lines[2]).at("checksum")));

  std::vector<std::string> t = lines;
  t.erase(t.begin() + 3);  // line 4 deleted: line 4 (was 5) no longer chains on line 3
  CHECK(error_of(t).pointer() == "line 4 /checksum");
  CHECK_THAT(error_of(t).expected(), Catch::Matchers::Contains("deleted, duplicated, moved"));
  t = lines;
  t.insert(t.begin() + 3, lines[3]);  // line 4 duplicated: the copy (line 5) breaks
  CHECK(error_of(t).pointer() == "line 5 /checksum");
  t = lines;
  std::swap(t[3], t[4]);  // lines 4 and 5 swapped
  CHECK(error_of(t).pointer() == "line 4 /checksum");
  t = lines;
  t.insert(t.begin() + 2, sealed(record(1, 7.0), json::parse(lines[1]).at("checksum")).dump());
  CHECK(error_of(t).pointer() == "line 4 /checksum");  // inserted as line 3, chained before it
  t = lines;
  json edited = json::parse(t[2]);
  edited["cost"] = 999;
  t[2] = edited.dump();  // edited, checksum kept
  CHECK(error_of(t).pointer() == "line 3 /checksum");
  t[2] = sealed(edited, json::parse(lines[1]).at("checksum")).dump();  // that line re-sealed
  CHECK(error_of(t).pointer() == "line 4 /checksum");
}

TEST_CASE("a forger who recomputes the chain is caught by the index check, or not at all",
          "[optimize][journal]") {
  TempDir d;
  const std::vector<std::string> lines = written_lines(d.path, 6);
  std::vector<std::string> t = lines;
  t.erase(t.begin() + 3);
  rechain(t, 3);
  InputError e = error_of(t);
  CHECK(e.pointer() == "line 4 /index");
  CHECK(e.expected().rfind("index 2 ", 0) == 0);
  CHECK(e.found() == "3");
  t = lines;
  t.insert(t.begin() + 3, lines[3]);  // a duplicate, re-chained
  rechain(t, 4);
  CHECK(error_of(t).pointer() == "line 5 /index");
  t = lines;
  std::swap(t[3], t[4]);
  rechain(t, 3);
  CHECK(error_of(t).pointer() == "line 4 /index");
  // An edited value with the chain recomputed passes every check on reading: only
  // evaluating the record again (--resume --verify) catches it.
  t = lines;
  json edited = json::parse(t[3]);
  edited["cost"] = 0.5;
  t[3] = edited.dump();
  rechain(t, 3);
  CHECK(parse_journal(joined(t), "j.jsonl").records[2].result.cost == 0.5);
}

TEST_CASE("format-1 journals are read and rewritten chained before anything is appended",
          "[optimize][journal]") {
  TempDir d;
  // A journal of an older pronk: no "format", each line sealed on its own.
  std::string old = sealed(header()).dump() + "\n";
  for (long i = 0; i < 4; ++i) old += sealed(record(i, 1.0 + i)).dump() + "\n";
  const std::string path = d.path + "/old.jsonl";
  std::ofstream(path, std::ios::binary) << old << sealed(record(4, 5.0)).dump().substr(0, 30);
  const JournalContents c = read_journal(path);
  CHECK(c.end.format == 1);
  CHECK(c.torn_tail);
  REQUIRE(c.records.size() == 4);
  // Appending: the torn line cut, the rest chained; the result is byte for byte what
  // JournalWriter writes for the same records from scratch.
  {
    JournalWriter w(path, header(), prepare_for_append(path, c.end));
    for (long i = 4; i < 6; ++i) w.append(record(i, 1.0 + i));
  }
  CHECK(slurp(path) == joined(written_lines(d.path, 6)));
  CHECK(read_journal(path).end.format == 2);
  // A format this pronk does not know is refused at the header.
  json h = header();
  h["format"] = 3;
  try {
    (void)parse_journal(sealed(h).dump() + "\n", "j.jsonl");
    FAIL("format 3 accepted");
  } catch (const InputError& e) {
    CHECK(e.pointer() == "line 1 /format");
  }
}

TEST_CASE("a torn tail of a chained journal is cut before appending", "[optimize][journal]") {
  TempDir d;
  const std::vector<std::string> lines = written_lines(d.path, 4);
  const std::string path = d.path + "/t.jsonl";
  std::vector<std::string> kept(lines.begin(), lines.begin() + 3);
  std::ofstream(path, std::ios::binary) << joined(kept) << lines[3].substr(0, 17);
  const JournalContents c = read_journal(path);
  CHECK(c.torn_tail);
  CHECK(c.end.good_bytes == joined(kept).size());
  {
    JournalWriter w(path, header(), prepare_for_append(path, c.end));
    for (long i = 2; i < 4; ++i) w.append(record(i, 1.0 + i));
  }
  CHECK(slurp(path) == joined(written_lines(d.path, 4)));
}

TEST_CASE("for_each_journal_record streams what read_journal reads", "[optimize][journal]") {
  TempDir d;
  written_lines(d.path, 5);
  const JournalContents all = read_journal(d.path + "/w.jsonl");
  std::vector<double> costs;
  for_each_journal_record(d.path + "/w.jsonl",
                          [&](const JournalRecord& r) { costs.push_back(r.result.cost); });
  REQUIRE(costs.size() == all.records.size());
  for (size_t i = 0; i < costs.size(); ++i) CHECK(costs[i] == all.records[i].result.cost);
}

TEST_CASE("the verification sample: N distinct records, seeded, or all", "[optimize][journal]") {
  const std::vector<long> a = verification_sample(100, 7, 42);
  REQUIRE(a.size() == 7);
  CHECK(std::set<long>(a.begin(), a.end()).size() == 7);
  CHECK(std::is_sorted(a.begin(), a.end()));
  CHECK(a.front() >= 0);
  CHECK(a.back() < 100);
  CHECK(verification_sample(100, 7, 42) == a);
  CHECK(verification_sample(100, 7, 43) != a);
  CHECK(verification_sample(5, 0, 1) == std::vector<long>{0, 1, 2, 3, 4});
  CHECK(verification_sample(5, 9, 1) == std::vector<long>{0, 1, 2, 3, 4});
  // Every record is drawn about equally often (Fisher-Yates is uniform): 10 of 20, 2000 seeds.
  std::vector<int> hits(20, 0);
  for (std::uint64_t s = 0; s < 2000; ++s)
    for (long i : verification_sample(20, 10, s)) ++hits[static_cast<size_t>(i)];
  for (int h : hits) CHECK(std::abs(h - 1000) < 120);  // binomial sd ~ 22
}

TEST_CASE("a journal header whose type is not a string is bad input, not a crash", "[journal]") {
  // The journal fuzzer's find: "type" holding an array made nlohmann throw a type_error past
  // the reader (std::terminate in the fuzzer, a raw exit 1 in the CLI).
  const std::string text =
      R"({"constr":0,"tylations":0,"spectral_radius":10,"strides":0,"type":[0.25,1.0]})"
      "\n";
  CHECK_THROWS_AS(parse_journal(text, "fuzz.jsonl"), InputError);
}
