// Input hardening below the CLI: the nesting bound every loader reads JSON
// through, the magnitude bound of unbounded numbers, the physical ranges of the
// loaders, and the study journal's per-line checksums.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "optimize/journal.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using pronk::io::InputError;

namespace {

InputError error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return InputError("", "", "", "");
}

}  // namespace

TEST_CASE("nesting depth is counted outside strings, escapes included", "[io][hardening]") {
  using pronk::io::json_nesting_depth;
  CHECK(json_nesting_depth("1") == 0);
  CHECK(json_nesting_depth("[[1], {\"a\": [2]}]") == 3);
  CHECK(json_nesting_depth(R"(["[[[[", "\"[[", "\\"])") == 1);
  CHECK(json_nesting_depth(std::string(100000, '[')) == 100000);
}

TEST_CASE("a file of 100000 nested arrays is refused before parsing", "[io][hardening]") {
  const std::string path = "/tmp/pronk_hardening_deep.json";
  std::ofstream(path) << std::string(100000, '[') << std::string(100000, ']');
  const InputError e = error_of([&] { (void)pronk::io::read_json_file(path); });
  CHECK(e.file() == path);
  CHECK(e.expected() == "JSON nested at most 128 levels deep");
  CHECK(e.found() == "arrays/objects nested 100000 levels deep");
  std::remove(path.c_str());
  // 128 levels are fine.
  CHECK(pronk::io::parse_json_text(std::string(128, '[') + std::string(128, ']'), "x").is_array());
}

TEST_CASE("numbers without a bound are bounded by kMaxInputMagnitude", "[io][hardening]") {
  const json doc = {{"a", 2e12}, {"b", -1e13}, {"c", 1e12}};
  pronk::io::JsonReader r(doc, "f.json", "");
  CHECK(r.number("c") == 1e12);
  CHECK(error_of([&] { (void)r.number("b"); }).expected() == "a finite number in [-1e+12, 1e+12]");
  CHECK(r.number_or("b", 0.0, -1e15) == -1e13);  // an explicit bound stands
  CHECK(error_of([&] { (void)r.number("a"); }).pointer() == "/a");
  CHECK(error_of([&] { (void)r.number_or("a", 0.0, -1e15); }).expected() ==
        "a finite number in [-1e+15, 1e+12]");
  CHECK(error_of([&] { (void)r.positive_or("a", 1.0); }).pointer() == "/a");
}

TEST_CASE("the loaders refuse masses and gravity outside physical ranges", "[io][hardening]") {
  const json mech = json::parse(R"({"kind": "mechanism",
    "bodies": [{"name": "b", "mass": 1e308, "inertia": [1, 1, 1]}]})");
  CHECK(error_of([&] { (void)pronk::io::parse_mechanism(mech, "m.json"); }).pointer() ==
        "/bodies/0/mass");
  json g = mech;
  g["bodies"][0]["mass"] = 1.0;
  g["gravity"] = {0, 0, -1e308};
  CHECK(error_of([&] { (void)pronk::io::parse_mechanism(g, "m.json"); }).pointer() == "/gravity/2");
  json point = mech;
  point.erase("bodies");
  point["masses"] = json::parse(R"([{"name": "p", "mass": 1e-9, "position": [0, 0, 1]}])");
  CHECK(error_of([&] { (void)pronk::io::parse_mechanism(point, "m.json"); }).pointer() ==
        "/masses/0/mass");
  const json scene = {{"body", {{"mass", 1e308}}}};
  CHECK(error_of([&] { (void)pronk::io::parse_scene(scene, "s.json"); }).pointer() == "/body/mass");
  // A pulse of 1e-300 s made the leg force (impulse / duration) infinite.
  const json pulse = {{"model", "pulse"}, {"pulse", {{"duration", 1e-300}}}};
  CHECK(error_of([&] { (void)pronk::io::parse_scene(pulse, "s.json"); }).pointer() ==
        "/pulse/duration");
}

TEST_CASE("journal lines carry checksums; a torn last line is dropped",
          "[io][journal][hardening]") {
  using pronk::optimize::parse_journal;
  using pronk::optimize::sealed;
  const json header = {{"type", "header"}, {"study_hash", "h"}};
  const json rec = {
      {"type", "evaluation"}, {"index", 0},   {"purpose", "objective"},      {"x", {0.5}},
      {"ok", true},           {"cost", 1.25}, {"constraints", json::array()}};
  const std::string good = sealed(header).dump() + "\n" + sealed(rec).dump() + "\n";
  const auto c = parse_journal(good, "j.jsonl");
  REQUIRE(c.records.size() == 1);
  CHECK(c.records[0].line_number == 2);
  CHECK(c.records[0].result.cost == 1.25);
  CHECK_FALSE(c.torn_tail);

  const auto torn = parse_journal(good + sealed(rec).dump().substr(0, 20), "j.jsonl");
  CHECK(torn.torn_tail);
  CHECK(torn.records.size() == 1);

  json edited = sealed(rec);
  edited["cost"] = 999;
  const InputError e = error_of([&] {
    (void)parse_journal(good + edited.dump() + "\n" + good.substr(good.find('\n') + 1), "j.jsonl");
  });
  CHECK(e.file() == "j.jsonl");
  CHECK(e.pointer() == "line 3 /checksum");
  CHECK_THAT(e.expected(), Contains("the journal was edited or corrupted"));
  CHECK(error_of([&] { (void)parse_journal(header.dump() + "\n", "j.jsonl"); }).found() ==
        "no checksum");
}
