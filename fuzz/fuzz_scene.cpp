// libFuzzer target over the scene loader and --set parsing. Input layout: the
// first line is a --set assignment, the rest a scene document. Any outcome but
// a crash, a sanitizer report or an exception other than InputError is fine.
#include "fuzz/fuzz_support.hpp"
#include "io/load/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t nl = input.find('\n');
  const std::string assignment = nl == std::string::npos ? std::string() : input.substr(0, nl);
  const std::string body = nl == std::string::npos ? input : input.substr(nl + 1);
  const auto parsed = pronk::fuzz::document(body);
  if (!parsed) return 0;
  nlohmann::json doc = *parsed;
  pronk::fuzz::expect_only_input_errors([&] {
    if (!assignment.empty()) pronk::io::apply_override(doc, assignment);
    const pronk::scene::Scene s = pronk::io::parse_scene(doc, "fuzz.json");
    // The resolved scene must load back to itself.
    (void)pronk::io::parse_scene(pronk::io::scene_to_json(s), "resolved.json");
  });
  return 0;
}
