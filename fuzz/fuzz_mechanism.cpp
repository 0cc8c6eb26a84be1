// libFuzzer target over the mechanism loader: the input is a mechanism document.
// A document that loads must load again from its resolved form.
#include "fuzz/fuzz_support.hpp"
#include "io/load/mechanism_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto doc = pronk::fuzz::document(pronk::fuzz::text(data, size));
  if (!doc) return 0;
  pronk::fuzz::expect_only_input_errors([&] {
    const pronk::io::LoadedMechanism m = pronk::io::parse_mechanism(*doc, "fuzz.json");
    (void)pronk::io::parse_mechanism(m.resolved, "resolved.json");
  });
  return 0;
}
