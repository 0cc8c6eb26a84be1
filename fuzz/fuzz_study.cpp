// libFuzzer target over the study loader: the input is a study document whose
// scene path resolves against the shipped studies (PRONK_STUDIES_DIR).
#include "fuzz/fuzz_support.hpp"
#include "optimize/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto doc = pronk::fuzz::document(pronk::fuzz::text(data, size));
  if (!doc) return 0;
  try {
    (void)pronk::optimize::parse_study(*doc, "fuzz.json", PRONK_STUDIES_DIR);
  } catch (const pronk::io::InputError&) {
  }
  return 0;
}
