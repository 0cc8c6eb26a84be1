// Robust design: random scenarios that perturb the robot itself. A perturbation draws one
// number of the resolved scene (a JSON Pointer), relative to its value or in an absolute range,
// uniform or normal (truncated to the range). It changes the robot (the plant) only: the
// controller keeps the nominal numbers (scene::ControllerModel). Every draw depends only on
// (seed, scenario index, perturbation index).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/scene/scene.hpp"

namespace pronk::io {
class JsonReader;
}

namespace pronk::optimize {

/// One perturbed number and its distribution.
struct PlantPerturbation {
  std::string pointer;        ///< into the resolved scene; "/body/inertia_tensor": the whole tensor
  bool relative = false;      ///< true: value x (1 + draw); false: the draw is the value
  double lo = 0.0, hi = 0.0;  ///< the range of the draw (a fraction when relative)
  bool normal = false;        ///< false: uniform in [lo, hi]; true: normal, truncated to it
  double sigma = 0.0;         ///< the normal's standard deviation (about (lo + hi) / 2)
};

/// One drawn value of a scenario.
struct PlantDraw {
  std::string pointer;
  bool relative = false;
  double value = 0.0;  ///< the fraction (relative) or the value itself
};

/// Draw number `k` of the perturbation `p` for the scenario whose generator seed is
/// `scenario_seed` (mix_seed(seed, index)): its own stream, so adding a perturbation shifts no
/// other draw and the start disturbances are drawn as without perturbations.
PlantDraw draw_perturbation(const PlantPerturbation& p, std::uint64_t scenario_seed, long k);

/// What a perturbation list is checked against: the resolved nominal scene, its model and the
/// settings that model ignores.
struct PerturbationContext {
  const nlohmann::json* resolved = nullptr;  ///< io::scene_to_json of the nominal scene
  scene::ModelKind model = scene::ModelKind::kImpulse;
  std::vector<std::string> unused;  ///< io::unused_settings of the nominal scene
  std::string scene_file;           ///< names the scene in errors of the scene itself
};

/// Reads the "perturb" array of a random scenario set (reader: the "random" object) and checks
/// it: every pointer names a number the model uses, every range keeps masses, inertias and
/// stiffnesses positive and the scene valid, and the inertia's principal moments satisfy the
/// triangle inequality at every corner of their ranges. Throws io::InputError.
std::vector<PlantPerturbation> parse_perturbations(io::JsonReader& random,
                                                   const PerturbationContext& context);

/// The scene document with the draws applied (relative ones to the document's own values).
nlohmann::json perturbed_document(const nlohmann::json& resolved,
                                  const std::vector<PlantDraw>& draws);

/// The robot perturbed by the draws, its controller keeping the numbers of `nominal`
/// (scene::ControllerModel). Throws io::InputError when the draws make no valid scene.
scene::Scene perturbed_scene(const scene::Scene& nominal, const std::vector<PlantDraw>& draws);

}  // namespace pronk::optimize
