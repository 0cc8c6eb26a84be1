// libFuzzer target over the study loaders, chosen as `pronk optimize` chooses: a staged
// study (with "stages") or a single one. The scene path resolves against the shipped
// studies (PRONK_STUDIES_DIR).
#include "fuzz/fuzz_support.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto doc = pronk::fuzz::document(pronk::fuzz::text(data, size));
  if (!doc) return 0;
  pronk::fuzz::expect_only_input_errors([&] {
    if (pronk::optimize::is_staged_study(*doc)) {
      (void)pronk::optimize::parse_staged_study(*doc, "fuzz.json", PRONK_STUDIES_DIR);
    } else {
      (void)pronk::optimize::parse_study(*doc, "fuzz.json", PRONK_STUDIES_DIR);
    }
  });
  return 0;
}
