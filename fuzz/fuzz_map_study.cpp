// libFuzzer target over the map study loader: the input is a map study document
// whose scene path resolves against the shipped studies (PRONK_STUDIES_DIR).
#include "fuzz/fuzz_support.hpp"
#include "optimize/map/map_study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto doc = pronk::fuzz::document(pronk::fuzz::text(data, size));
  if (!doc) return 0;
  pronk::fuzz::expect_only_input_errors(
      [&] { (void)pronk::optimize::map::parse_map_study(*doc, "fuzz.json", PRONK_STUDIES_DIR); });
  return 0;
}
