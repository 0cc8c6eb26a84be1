// End-to-end: a study whose scenarios perturb the robot (studies/robust_pulse_example.json)
// through `pronk optimize` and `pronk reproduce`, and its bad input (exit 2).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

using namespace cli_support;
using nlohmann::json;

namespace {
const std::string kStudies = std::string(PRONK_SOURCE_DIR) + "/studies/";

// The numbers of a summary.md table row "| name | a | b |".
std::vector<double> row(const std::string& md, const std::string& name) {
  const size_t at = md.find("| " + name + " | ");
  if (at == std::string::npos) return {};
  std::vector<double> v;
  std::string line = md.substr(at, md.find('\n', at) - at);
  size_t p = line.find('|', 2);
  while (p != std::string::npos && p + 1 < line.size()) {
    const size_t q = line.find('|', p + 1);
    if (q == std::string::npos) break;
    v.push_back(std::stod(line.substr(p + 1, q - p - 1)));
    p = q;
  }
  return v;
}
}  // namespace

TEST_CASE("a robust study reports its tuned design on the nominal and the perturbed robots",
          "[cli][optimize][perturb]") {
  TempDir d("robust_cli");
  const Run r = pronk(d, {"optimize", kStudies + "robust_pulse_example.json", "--out", d / "o"});
  REQUIRE(r.code == 0);
  const std::string md = slurp(d / "o/summary.md");
  CHECK(md.find("| metric | nominal robot | perturbed robot |") != std::string::npos);
  // The last "stabilized" row is the comparison's: two fractions of 16 trials.
  const size_t cmp = md.find("| metric | nominal robot | perturbed robot |");
  const std::vector<double> stab = row(md.substr(cmp), "stabilized");
  REQUIRE(stab.size() == 2);
  // The objective's term mean(stabilized) repeats the row stabilized: it is not shown again.
  CHECK(md.find("| mean(stabilized) |") == std::string::npos);
  // The study computes no stride map ("stability": false): no spectral radius row reading 0.
  CHECK(md.find("| spectral_radius |") == std::string::npos);
  for (double f : stab) {
    CHECK(f >= 0.0);
    CHECK(f <= 1.0);
    CHECK(f * 16 == Approx(std::round(f * 16)).margin(1e-9));
  }
  // design.json carries the perturbations in its study, and reproduce replays them.
  const json design = json::parse(slurp(d / "o/design.json"));
  CHECK(design.at("study_document").at("validation").at("random").at("perturb").size() == 2);
  const Run rep = pronk(d, {"reproduce", d / "o/design.json"});
  CHECK(rep.code == 0);
}

TEST_CASE("a robust study whose inertia ranges break the triangle inequality exits 2",
          "[cli][optimize][perturb]") {
  TempDir d("robust_cli");
  json st = json::parse(slurp(kStudies + "robust_pulse_example.json"));
  st["scene"] = kStudies + "scenes/legged_pulse_duty50.json";
  st["validation"]["random"]["perturb"] = json::array();
  for (int k = 0; k < 3; ++k) {
    const std::string i = std::to_string(k);
    st["validation"]["random"]["perturb"].push_back(
        {{"pointer", "/body/inertia_tensor/" + i + "/" + i}, {"relative", {-0.2, 0.2}}});
  }
  write_file(d / "bad.json", st.dump());
  const Run r = pronk(d, {"optimize", d / "bad.json", "--out", d / "o"});
  check_bad_input(r, d / "bad.json" + ": /validation/random/perturb: expected inertia ranges");
  CHECK(r.err.find("triangle inequality") != std::string::npos);
  st["validation"]["random"]["perturb"] = {
      {{"pointer", "/pseudo_rigid/leg_stiffness"}, {"relative", {-0.15, 0.15}}}};
  write_file(d / "bad.json", st.dump());
  check_bad_input(pronk(d, {"optimize", d / "bad.json", "--out", d / "o"}),
                  d / "bad.json" +
                      ": /validation/random/perturb/0/pointer: expected a number "
                      "the pulse model uses");
}
