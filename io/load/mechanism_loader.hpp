// Reads a generic pseudo-rigid `mechanism` scene (docs/pseudorigid.md) with the strict
// reader of json_reader.hpp: unknown keys are errors and every error is an
// io::InputError naming file, JSON Pointer, what was expected and what was found.
//
// Document (units SI; every key except "kind" and "masses"/"bodies" optional):
//   "kind": "mechanism", "name": string, "gravity": [gx, gy, gz] [m/s^2]
//   "masses":  [{"name", "mass" [kg], "position" [m], "velocity" [m/s]}]
//   "anchors": [{"name", "position" [m]}]                      grounded points
//   "bodies":  [{"name", "mass" [kg], "inertia": [Ixx, Iyy, Izz] or a 3x3 tensor [kg m^2],
//                "com" [m], "attitude_deg": [a1, a2, a3], "attitude_set": "123"|"313",
//                "velocity" [m/s], "omega" [rad/s, world] or "euler_rates" [rad/s],
//                "internal_stiffness" [N/m], "internal_damping" [N s/m],
//                "ghost_points": [{"name", "position" [m, body frame rel. CoM]}],
//                "reference_points": [{"name", "position"}],
//                "dummy_masses": [{"name", "position", "ratio"}]}]
//     a body's four masses are nodes "<body>.0" .. "<body>.3"
//   "connections": [{"name", "a", "b" (node names), "class": "other"|"leg"|"internal"|"actuator",
//                "stiffness" [N/m], "rest_length" [m] or "initial", "damping" [N s/m],
//                "friction" [N s/m], "drag" [N s^2/m^2], "force_limit" [N]}]
//   "surfaces": [{"name", "type": "plane"|"line"|"point", "body" (attached; else grounded),
//                "point" [m; world, or body frame when attached], "direction" (normal or line),
//                "nodes": [names], "stiffness" [N/m], "damping" [N s/m]}]
//   "forces":  [{"name", "frame": "world"|"body", "node", "body", "force" [N],
//                "t_start" [s], "t_end" [s]}]
//   "actuators": [{"name", "type": "impulse", "node", "body", "direction", "force" [N],
//                "impulse" [N s], "t_start" [s]}]
//   "simulation": {"t_end", "output_interval" [s], "method": auto|euler|rk2|rk4|dopri5|rodas4|
//                radau5|cvode_bdf|verlet (default auto: method_choice.hpp picks the
//                method and its step or tolerances, replacing rtol/atol or h_fixed/energy_tol),
//                "accuracy" (auto's target: largest sampled energy-balance drift relative to
//                the energy scale, 1e-12..0.5, default 1e-3; ignored by the other methods), "rtol",
//                "atol", "h_fixed", "h_initial", "h_max", "h_min" [s], "max_steps", "energy_tol"
//                (verlet: bound on its bounded energy term per step, relative to the run's energy
//                scale; sub-steps h_fixed where needed; 0 = off), "max_steps_per_second" [1/s]
//                (crawl guard, 0 = off), "dense_lu_max_dimension", "cvode_linear_solver":
//                "auto"|"dense"|"klu", "error_norm": "state"|"body",
//                "euler_set": "123"|"313", "energy_blowup_factor", "check_jacobian",
//                "zero_length_epsilon" [m], "ghost_transfer": "barycentric" (default, conservative)
//                or "min_norm", "internal_stiffness": N/m or "auto", "contact_stiffness": N/m or
//                "auto", "strain_budget", "penetration_budget" [m], "load_factor"}
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"
#include "sim/pseudorigid/method_choice.hpp"
#include "sim/pseudorigid/model.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/stiffness.hpp"

namespace pronk::io {

/// A loaded mechanism scene.
struct LoadedMechanism {
  pseudorigid::Mechanism mechanism;
  pseudorigid::StiffnessChoice stiffness;  ///< what "auto" chose (zeros when not auto)
  bool internal_auto = false, contact_auto = false;
  bool method_auto = false;                 ///< "method": "auto"
  pseudorigid::MethodChoice method_choice;  ///< what auto chose (when method_auto)
  /// The input document with every simulation setting explicit and "auto"
  /// stiffnesses replaced by the chosen numbers: loading it gives the same mechanism.
  nlohmann::json resolved;
};

/// True when the document's top-level "kind" is "mechanism".
bool is_mechanism_document(const nlohmann::json& doc);

/// Builds the mechanism; `file` names the source in error messages.
LoadedMechanism parse_mechanism(const nlohmann::json& doc, const std::string& file);

/// Runs the loaded mechanism (pseudorigid::simulate). Under auto, a completed run whose
/// sampled energy-balance drift misses the accuracy is rerun once with
/// pseudorigid::refine_choice; `loaded`'s mechanism, method_choice and resolved document then
/// hold the rerun's setting (the resolved scene reruns the rerun), and the summary's counters
/// and wall time are both runs' sum. (io/load/mechanism_run.cpp)
pseudorigid::RunSummary simulate_loaded(LoadedMechanism* loaded);

}  // namespace pronk::io
