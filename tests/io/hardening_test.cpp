// Input hardening below the CLI: the strict JSON reading every loader goes through
// (nesting bound, a key given twice, a NUL byte, trailing bytes), JSON Pointers from the
// user resolved without throwing, names that become directories, the magnitude bound of
// unbounded numbers, the physical ranges of the loaders, and the study journal's per-line
// checksums.
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
#include "io/load/json_text.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
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

/// The InputError of reading `text` as a file.
InputError text_error(const std::string& text) {
  return error_of([&] { (void)pronk::io::parse_json_text(text, "in.json"); });
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

TEST_CASE("a key given twice in one object is refused, naming its pointer", "[io][json]") {
  InputError e = text_error(R"({"model": "impulse", "name": "x", "model": "pulse"})");
  CHECK(e.file() == "in.json");
  CHECK(e.pointer() == "/model");
  CHECK(e.expected() == "each key once in an object");
  CHECK_THAT(e.found(), StartsWith("\"model\" a second time"));
  // Deep inside arrays and objects, with escaped keys.
  e = text_error(R"({"a": [0, {"b": 1}, [2, {"c/d": {"~k": 1, "x": [], "~k": 2}}]]})");
  CHECK(e.pointer() == "/a/2/1/c~1d/~0k");
  e = text_error(R"([{"k": 1}, {"k": 2, "k": 3}])");
  CHECK(e.pointer() == "/1/k");
  // The same key in different objects, and at different depths, is fine: the plain parse.
  const std::string ok = R"({"k": {"k": [{"k": 1}, {"k": 2}]}, "j": {"k": 3}, "l": [[], {}]})";
  CHECK(pronk::io::parse_json_text(ok, "in.json") == json::parse(ok));
}

TEST_CASE("a NUL byte and trailing bytes after the document are refused", "[io][json]") {
  // nlohmann's parser stops at a NUL: "{} NUL garbage" used to read as {}.
  const std::string nul = std::string("{\"name\": \"x\"}\n") + '\0' + "garbage";
  InputError e = text_error(nul);
  CHECK(e.pointer() == "");
  CHECK(e.expected() == "JSON without NUL bytes");
  CHECK(e.found() == "a NUL byte at byte offset 14 (of 22)");
  e = text_error(std::string("{}") + '\0');
  CHECK(e.found() == "a NUL byte at byte offset 2 (of 3)");
  e = text_error("{\"name\": \"x\"} {\"name\": \"y\"}");
  CHECK(e.expected() == "valid JSON");
  CHECK_THAT(e.found(), Contains("expected end of input"));
  CHECK(pronk::io::parse_json_text("{}\n \t\r\n", "in.json") == json::object());
}

TEST_CASE("values given with --set are read as strictly as files (unit)", "[io][json]") {
  using pronk::io::parse_json_value;
  CHECK(*parse_json_value("[1, {\"a\": 2}]", "cl", "/p") == json::parse("[1, {\"a\": 2}]"));
  CHECK_FALSE(parse_json_value("a bare word", "cl", "/p").has_value());
  InputError e = error_of([] { (void)parse_json_value(R"({"a": 1, "a": 2})", "cl", "/p"); });
  CHECK(e.file() == "cl");
  CHECK(e.pointer() == "/p/a");
  e = error_of([] { (void)parse_json_value(std::string("1") + '\0' + "2", "cl", "/p"); });
  CHECK(e.expected() == "a value without NUL bytes");
  // Through apply_override: the duplicate's pointer is below the --set pointer.
  json doc = {{"controller", {{"kp", {1, 2}}}}};
  e = error_of(
      [&] { pronk::io::apply_override(doc, R"(/controller={"kp": [1, 2], "kp": [3, 4]})"); });
  CHECK(e.file() == R"(command line (--set /controller={"kp": [1, 2], "kp": [3, 4]}))");
  CHECK(e.pointer() == "/controller/kp");
}

TEST_CASE("find_pointer resolves user pointers without throwing", "[io][json]") {
  using pronk::io::find_pointer;
  const json doc = json::parse(R"({"a": [10, 11, {"b": 12}], "m/n": 13, "t~": 14, "": 15,
                                   "s": "text"})");
  // Where a value exists, the same one nlohmann's at() finds.
  for (const char* p : {"", "/a", "/a/0", "/a/2/b", "/m~1n", "/t~0", "/"}) {
    INFO(p);
    REQUIRE(find_pointer(doc, p) != nullptr);
    CHECK(*find_pointer(doc, p) == doc.at(json::json_pointer(p)));
  }
  // No value: nullptr, where nlohmann throws (out_of_range 404 "unresolved reference token
  // ''" for the first two, from contains() itself).
  for (const char* p :
       {"/a/", "/a/99999999999999999999999", "/a/3", "/a/01", "/a/-", "/a/+1", "/a/ 1", "/a/1e0",
        "/s/0", "/s/", "/a/0/x", "/nope", "a", "/m~2n", "/t~", "/a/2/b/"}) {
    INFO(p);
    CHECK(find_pointer(doc, p) == nullptr);
  }
  CHECK_THROWS_AS(doc.contains(json::json_pointer("/a/")), json::out_of_range);
  json mutable_doc = doc;
  *find_pointer(mutable_doc, "/a/1") = 5;
  CHECK(mutable_doc["a"][1] == 5);
}

TEST_CASE("names used as directory names must be plain", "[io][json]") {
  using pronk::io::path_name_problem;
  for (const char* good : {"scene", "study 2", "a.b", "..x", "x..", "ünï", "-"}) {
    CHECK(path_name_problem(good).empty());
  }
  CHECK(path_name_problem("") == "an empty name");
  CHECK(path_name_problem(".") == "\".\", which names a directory itself");
  CHECK(path_name_problem("..") == "\"..\", which names a directory itself");
  CHECK(path_name_problem("a/b") == "\"a/b\", which has a '/'");
  CHECK(path_name_problem("/") == "\"/\", which has a '/'");
  CHECK(path_name_problem("a\nb") == "a control character (byte 10) at byte 1");
  CHECK(path_name_problem("ab\x7f") == "a control character (byte 127) at byte 2");
  CHECK(path_name_problem(std::string(255, 'x')).empty());
  CHECK(path_name_problem(std::string(256, 'x')) == "a name of 256 bytes");
  // Through the reader: the name's pointer, the rule, the problem.
  const json doc = {{"name", ".."}};
  pronk::io::JsonReader r(doc, "s.json", "");
  const InputError e = error_of([&] { (void)r.path_name_or("name", "x"); });
  CHECK(e.pointer() == "/name");
  CHECK_THAT(e.expected(), StartsWith("a name usable as a directory name"));
  CHECK(e.found() == "\"..\", which names a directory itself");
  CHECK(pronk::io::JsonReader(json::object(), "s.json", "").path_name_or("name", "d") == "d");
}
