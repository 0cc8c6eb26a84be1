#include "io/load/auto_solver_input.hpp"

#include <string>

#include "sim/pseudorigid/method_choice.hpp"

namespace pronk::io {

void refuse_auto_chosen_settings(JsonReader& solver, const nlohmann::json& node) {
  for (const char* key : pseudorigid::kAutoChosenSettings) {
    if (!solver.has(key)) continue;
    solver.optional(key);
    const std::string method =
        solver.has("method") ? "\"method\": \"auto\"" : "\"method\": \"auto\" (the default)";
    throw solver.error(key,
                       std::string("no ") + key + " under " + method +
                           ", which chooses it; name a method (e.g. \"rodas4\" or \"verlet\") "
                           "to set it, or set \"accuracy\"",
                       describe(node.at(key)));
  }
}

}  // namespace pronk::io
